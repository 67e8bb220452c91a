// Domains of the basis functions and their neighbour graph (paper 2.3 eq. 8 and 4; thesis 2.5).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/sparse.h"

namespace qf {

struct DomainOptions {
  double tau = 0.05;           // D_k = {x : Psi_k(x) > tau} (paper; the thesis used 0.01)
  bool strict = false;         // thesis 2.5: each point only in its argmax function's domain
  double neighbor_share = 0.05;  // i ~ j when |D_i n D_j| > share |D_i| or > share |D_j| (paper 4)
};

struct Domains {
  // Points of domain d: points[offsets[d] .. offsets[d+1]), increasing. One domain per basis
  // function (column of Psi), so some may be empty.
  std::vector<std::uint32_t> offsets, points;
  std::vector<std::array<std::uint32_t, 2>> edges;  // neighbour graph, i < j, sorted
  std::size_t empty = 0;          // basis functions whose weights never exceed tau
  std::size_t uncovered = 0;      // points in no domain (all their weights <= tau)
  std::size_t shared_points = 0;  // points in two or more domains

  std::size_t count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t size(std::size_t d) const { return offsets[d + 1] - offsets[d]; }
};

// Domains of Psi (n points x m functions) and their neighbour graph.
Domains make_domains(const SparseMatrix& psi, const DomainOptions& options = {});

// Psi restricted to the domains (entry (x, d) kept only for x in D_d) with each point's row
// renormalised to sum 1; rows of uncovered points stay empty. The textures' alpha comes from this:
// the weights at or below tau that the domains leave out would otherwise be missing from the
// rendered sum (measured: ~5% of the alpha mass on a sphere at 83 domains, seen as see-through).
SparseMatrix domain_partition(const SparseMatrix& psi, const Domains& domains);

// Index of the largest weight in each row of Psi (lowest index on ties); n entries.
std::vector<std::uint32_t> strongest_function(const SparseMatrix& psi);

}  // namespace qf
