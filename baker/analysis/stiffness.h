// The FEM stiffness matrix of the classifier-weighted diffusion operator -div(C grad) on the point
// set, assembled on the local Delaunay fans (paper 2.2, eqs. 5-7).
//
// Sign convention: A is the usual stiffness matrix, i.e. symmetric POSITIVE semi-definite with
//   A_ij = 1/2 (At_ij + At_ji)  for i != j,   At_ij = sum over i's fan triangles T containing j of
//          C(T) grad(Phi_i) . grad(Phi_j) |T| = -1/2 C(T) cot(angle opposite edge ij in T),
//   A_ii = -sum_{j != i} A_ij  (every row sums to 0; constants are in the kernel).
// Off-diagonals are negative where the opposite angles are acute (strong coupling inside flat
// regions, weak across creases, where C is small) and positive across obtuse angles. Entries are
// dimensionless: A does not change when the point set is scaled uniformly.
#pragma once

#include <cstdint>
#include <vector>

#include "analysis/fans.h"
#include "core/sparse.h"

namespace qf {

struct StiffnessReport {
  std::size_t zero_area_triangles = 0;  // fan triangles skipped: their 3D area is ~0 (coincident or collinear points)
  std::size_t empty_rows = 0;           // points with no coupling at all (isolated; their row is 0)
  std::size_t one_sided_pairs = 0;      // couplings present in only one of the two points' fans
};

// Assembles A (n x n) from the fans, the 3D positions and the per-point classifier (C > 0).
// Triangles whose area is below 1e-12 of their squared longest edge are skipped and counted, so
// A never holds NaN or Inf. Uses every core; the result does not depend on the thread count.
SparseMatrix assemble_stiffness(const std::vector<Vec3f>& positions, const Fans& fans,
                                const std::vector<float>& classifier, StiffnessReport* report = nullptr);

}  // namespace qf
