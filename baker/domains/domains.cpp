// Thresholded (or strict) domains and the overlap-based neighbour graph.
#include "domains/domains.h"

#include <algorithm>

namespace qf {

std::vector<std::uint32_t> strongest_function(const SparseMatrix& psi) {
  std::vector<std::uint32_t> best(static_cast<std::size_t>(psi.rows()), 0);
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    double w = -1;
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it)
      if (it.value() > w) w = it.value(), best[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(it.col());
  }
  return best;
}

Domains make_domains(const SparseMatrix& psi, const DomainOptions& options) {
  const auto n = static_cast<std::size_t>(psi.rows()), m = static_cast<std::size_t>(psi.cols());
  Domains d;
  // 1. Membership lists per point (columns increasing).
  std::vector<std::uint32_t> member_offsets(n + 1, 0), members;
  const std::vector<std::uint32_t> argmax = options.strict ? strongest_function(psi) : std::vector<std::uint32_t>();
  for (std::size_t i = 0; i < n; ++i) {
    if (options.strict) {
      if (psi.outerIndexPtr()[i + 1] > psi.outerIndexPtr()[i]) members.push_back(argmax[i]);
    } else {
      for (SparseMatrix::InnerIterator it(psi, static_cast<Eigen::Index>(i)); it; ++it)
        if (it.value() > options.tau) members.push_back(static_cast<std::uint32_t>(it.col()));
    }
    member_offsets[i + 1] = static_cast<std::uint32_t>(members.size());
    const std::uint32_t k = member_offsets[i + 1] - member_offsets[i];
    d.uncovered += k == 0;
    d.shared_points += k >= 2;
  }
  // 2. Invert into point lists per domain (points come out increasing).
  d.offsets.assign(m + 1, 0);
  for (std::uint32_t f : members) ++d.offsets[f + 1];
  for (std::size_t f = 0; f < m; ++f) d.offsets[f + 1] += d.offsets[f];
  d.points.resize(members.size());
  std::vector<std::uint32_t> fill(d.offsets.begin(), d.offsets.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t r = member_offsets[i]; r < member_offsets[i + 1]; ++r) d.points[fill[members[r]]++] = static_cast<std::uint32_t>(i);
  for (std::size_t f = 0; f < m; ++f) d.empty += d.size(f) == 0;
  // 3. Shared points per pair of domains, then the neighbour test.
  std::vector<std::uint64_t> pairs;
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t a = member_offsets[i]; a < member_offsets[i + 1]; ++a)
      for (std::uint32_t b = a + 1; b < member_offsets[i + 1]; ++b)
        pairs.push_back(std::uint64_t{members[a]} << 32 | members[b]);
  std::sort(pairs.begin(), pairs.end());
  for (std::size_t p = 0; p < pairs.size();) {
    std::size_t q = p;
    while (q < pairs.size() && pairs[q] == pairs[p]) ++q;
    const auto i = static_cast<std::uint32_t>(pairs[p] >> 32), j = static_cast<std::uint32_t>(pairs[p]);
    const double shared = double(q - p);
    if (shared > options.neighbor_share * double(d.size(i)) || shared > options.neighbor_share * double(d.size(j)))
      d.edges.push_back({i, j});
    p = q;
  }
  return d;
}

SparseMatrix domain_partition(const SparseMatrix& psi, const Domains& domains) {
  const auto n = static_cast<std::size_t>(psi.rows());
  // 1. The rows' shape: each point's domains, in increasing order (a counting sort of the
  //    domains' point lists), written straight into compressed rows; no triplets and no
  //    column-major temporary (~40 bytes a membership at the peak, ~1 s a level at 1M points).
  SparseMatrix out(psi.rows(), psi.cols());
  out.resizeNonZeros(static_cast<Eigen::Index>(domains.points.size()));
  std::int32_t* outer = out.outerIndexPtr();
  std::fill(outer, outer + n + 1, 0);
  for (std::uint32_t x : domains.points) ++outer[x + 1];
  for (std::size_t i = 0; i < n; ++i) outer[i + 1] += outer[i];
  std::vector<std::int32_t> fill(outer, outer + n);
  for (std::size_t d = 0; d < domains.count(); ++d)
    for (std::uint32_t q = domains.offsets[d]; q < domains.offsets[d + 1]; ++q) {
      const std::uint32_t x = domains.points[q];
      const auto k = static_cast<std::size_t>(fill[x]++);
      out.innerIndexPtr()[k] = static_cast<std::int32_t>(d);
      out.valuePtr()[k] = psi.coeff(x, static_cast<Eigen::Index>(d));
    }
  // 2. Each row over its sum, summed in increasing domain order.
  double* value = out.valuePtr();
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) sum += value[k];
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) value[k] /= sum;
  }
  return out;
}

}  // namespace qf
