// Basis functions of the AMG hierarchy (paper 2.3; amg-notes section 4 step 8):
// Psi_l = P_1 P_2 ... P_l, n x m_l, one column per basis function, rows in point order.
#pragma once

#include <functional>

#include "amg/hierarchy.h"

namespace qf {

struct BasisOptions {
  // Weights below this are dropped after each product and the row rescaled to sum 1 again
  // (amg-notes 3.4: keeps Psi at ~7-14 entries per point instead of filling in). 0 = exact.
  double prune = 1e-3;
};

// Psi at one level (0 = identity, 1 .. level_count() - 1). Non-negative, rows summing to 1. The
// same matrices as for_each_basis (pruning applies after each product, in the same order).
SparseMatrix basis_at_level(const AmgHierarchy& h, std::size_t level, const BasisOptions& options = {});

// Calls visit(level, Psi_level) for levels 1 .. last in order, computing each from the previous
// one; only one Psi is held at a time.
void for_each_basis(const AmgHierarchy& h, std::size_t last, const BasisOptions& options,
                    const std::function<void(std::size_t, const SparseMatrix&)>& visit);

}  // namespace qf
