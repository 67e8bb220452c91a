// Basis functions Psi_l = P_1 ... P_l, with pruning and renormalisation.
#include "amg/basis.h"

#include <stdexcept>

namespace qf {

void for_each_basis(const AmgHierarchy& h, std::size_t last, const BasisOptions& options,
                    const std::function<void(std::size_t, const SparseMatrix&)>& visit) {
  if (last >= h.level_count()) throw std::out_of_range("basis level " + std::to_string(last) + " does not exist");
  // P_1's rows are in the hierarchy's fine order: put them in point order once, and every later
  // product Psi_{l-1} P_l keeps that row order.
  SparseMatrix psi;
  for (std::size_t l = 1; l <= last; ++l) {
    psi = l == 1 ? scatter_rows(h.P[0], h.fine_order) : sparse_product(psi, h.P[l - 1], options.prune);
    visit(l, psi);
  }
}

SparseMatrix basis_at_level(const AmgHierarchy& h, std::size_t level, const BasisOptions& options) {
  if (level == 0) {
    const auto n = static_cast<Eigen::Index>(h.levels.empty() ? 0 : h.levels[0].size);
    SparseMatrix identity(n, n);
    identity.setIdentity();
    return identity;
  }
  SparseMatrix out;
  for_each_basis(h, level, options, [&](std::size_t l, const SparseMatrix& psi) {
    if (l == level) out = psi;
  });
  return out;
}

}  // namespace qf
