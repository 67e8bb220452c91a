// Sparse matrices (Eigen, compressed rows) and the few operations the stages share: building
// from raw rows, exact symmetrisation with zero row sums, and the Galerkin product P^T A P.
#pragma once

#include <Eigen/SparseCore>

#include <cstdint>
#include <vector>

namespace qf {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, std::int32_t>;

// A rows x cols matrix from compressed rows (outer: rows + 1 offsets; inner: sorted columns).
SparseMatrix from_rows(Eigen::Index rows, Eigen::Index cols, const std::vector<std::int32_t>& outer,
                       const std::vector<std::int32_t>& inner, const std::vector<double>& values);

struct SymmetrizeReport {
  std::size_t one_sided = 0;   // off-diagonal pairs present on one side only
  std::size_t empty_rows = 0;  // rows left without any off-diagonal entry
};

// S_ij = (A_ij + A_ji) / 2 for i != j (a missing side counts as 0), S_ii = -sum_{j != i} S_ij.
// Both sides of a pair add the same two numbers, so S is exactly symmetric. Off-diagonals with
// |S_ij| <= drop * max(|A_ii|, |A_jj|) are removed first (drop = 0 keeps all but exact zeros).
// Every row gets a diagonal entry (0 for an empty row). A must be square.
SparseMatrix symmetrize_zero_row_sums(const SparseMatrix& a, double drop = 0.0, SymmetrizeReport* report = nullptr);

// A_c = P^T A P for A (n x n) and P (n x m), row by row over every core; each entry is summed in
// a fixed order, so the result does not depend on the thread count.
SparseMatrix galerkin_product(const SparseMatrix& a, const SparseMatrix& p);

// C = A B (A: n x k, B: k x m), row by row over every core, entries summed in a fixed order.
// With prune > 0, each row of C then loses its entries below `prune` (its largest entry is always
// kept) and is rescaled to its former sum: for row-stochastic A and B, C stays row-stochastic.
SparseMatrix sparse_product(const SparseMatrix& a, const SparseMatrix& b, double prune = 0.0);

// The matrix whose row order[r] is row r of `m` (order is a permutation of the rows).
SparseMatrix scatter_rows(const SparseMatrix& m, const std::vector<std::uint32_t>& order);

}  // namespace qf
