// Algebraic multigrid coarsening of the stiffness matrix into a hierarchy of prolongations
// (paper 2.3; thesis 2.4; shared/design/amg-notes.md section 4).
//
// Level 0 is the point set itself (n functions, Psi_0 = identity); level l has m_l basis
// functions, the columns of Psi_l = P_1 P_2 ... P_l (n x m_l). Every P_l is non-negative with rows
// summing to 1, so every Psi_l is a partition of unity. The coarsest level is L = levels() - 1;
// the paper counts back from it ("L-5").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/sparse.h"

namespace qf {

struct AmgOptions {
  double theta = 0.25;           // strength of connection: -a_ij >= theta max_k(-a_ik) (amg-notes 1.1)
  double target_ratio_min = 2.0;  // coarsening ratio n_l / n_{l+1} aimed for; the paper: "between 2 and 3"
  double target_ratio_max = 3.0;
  int ratio_tries = 6;            // splits tried per level, bisecting theta, to land in the target range
  std::size_t stop_size = 9;      // stop below ~10 basis functions
  int max_levels = 25;
  // Level sizes to aim at (qf-bake --aim-primitives: the --primitives counts), largest first;
  // empty = the ratio rule alone. From a level 1.5 to 27 times a target not yet reached, the next
  // levels are coarsened to land on the target in one to three even steps (theta bisected on the
  // count, up to kAimTries splits) instead of into the ratio range. So two decompositions of one surface at
  // different densities (an out-of-core bake's subsample and the whole set) get levels of the
  // same sizes, which the nearest-count level choice alone does not give (a factor of 2-3 apart).
  std::vector<std::size_t> target_sizes;
};
constexpr int kAimTries = 14;

struct AmgLevel {
  std::size_t size = 0;  // basis functions on this level
  double theta = 0;      // strength threshold used to make it from the level above
  double ratio = 0;      // size of the finer level / size
  double split_seconds = 0, galerkin_seconds = 0;  // wall clock (reports only; never written to files)
};

struct AmgHierarchy {
  // The finest level is coarsened in breadth-first order of the matrix graph, which keeps
  // couplings close in memory (3x faster Galerkin products on shuffled inputs): row r of P[0] is
  // point fine_order[r]. Coarser levels are numbered in the order of the level above.
  std::vector<std::uint32_t> fine_order;
  std::vector<SparseMatrix> P;   // P[l-1] maps level l to level l-1: rows m_{l-1}, columns m_l
  std::vector<AmgLevel> levels;  // levels[0] = the points
  std::size_t components = 0;    // connected parts of the finest matrix graph (a floor for the coarsest size)
  std::size_t isolated = 0;      // points without any coupling (each stays its own function)

  std::size_t level_count() const { return levels.size(); }
};

// Builds the hierarchy from A (symmetric, zero row sums; see stiffness.h). Ruge-Stueben splitting
// (first and second pass) with ties broken deterministically, direct interpolation with positive
// and weak couplings lumped (w_ij = a_ij / sum_{k in C_i} a_ik >= 0, rows summing to exactly 1),
// Galerkin A_{l+1} = P^T A_l P with zero row sums restored and symmetry enforced, theta bisected
// per level until the ratio lies in [target_ratio_min, target_ratio_max] (or the closest try).
// Stops at stop_size functions, at max_levels, or when coarsening stalls (ratio < 1.1, e.g. only
// disconnected parts are left). Deterministic: no randomness, no dependence on thread count.
AmgHierarchy build_hierarchy(const SparseMatrix& a, const AmgOptions& options = {});
// The same, freeing `a` as soon as it is renumbered (for a large set the finest matrix is the
// biggest one; a is left empty).
AmgHierarchy build_hierarchy(SparseMatrix&& a, const AmgOptions& options = {});

// Level by its number: k >= 0 counts from the finest (0 = the points themselves), k < 0 back from
// the coarsest L = level_count() - 1 (k = -5 is the paper's "L-5"). Throws std::out_of_range.
std::size_t level_by_index(const AmgHierarchy& h, long long k);

// The level whose number of basis functions is nearest `primitives` (the coarser one on ties).
std::size_t level_by_primitives(const AmgHierarchy& h, std::size_t primitives);

// A stable 64-bit fingerprint of the hierarchy (sizes, structure and values of every P): the first
// 8 bytes of their SHA-256.
std::uint64_t hierarchy_hash(const AmgHierarchy& h);

}  // namespace qf
