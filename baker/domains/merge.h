// Greedy domain merging (thesis 3.4): two overlapping domains that are both flat and face the same
// way become one basis function (their sum), biggest overlap first, until no pair qualifies.
#pragma once

#include <cstddef>
#include <vector>

#include "core/types.h"
#include "domains/domains.h"

namespace qf {

struct MergeOptions {
  // Flatness: the surface variation lambda_min / (lambda0 + lambda1 + lambda2) of the domain's
  // Psi-weighted point distribution (thesis 3.2's curvature metric) must not exceed this.
  double max_variation = 0.01;
  double max_angle_degrees = 10.0;  // between the two domains' planes
  DomainOptions domains;            // tau for the overlaps
};

struct MergeReport {
  std::size_t merges = 0;
  std::size_t before = 0, after = 0;  // basis functions
};

// Returns Psi' = Psi M, M merging columns into groups (numbered in order of their first member).
// Rows keep summing to 1. The overlap of a merged domain with another is taken as the sum of its
// members' overlaps with it (points in three domains count more than once): it orders the merges.
SparseMatrix merge_domains(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const MergeOptions& options = {},
                           MergeReport* report = nullptr);

}  // namespace qf
