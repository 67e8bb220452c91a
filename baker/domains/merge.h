// Greedy domain merging (thesis 3.4): two overlapping domains that are both flat and face the same
// way become one basis function (their sum), biggest overlap first, until no pair qualifies. Then
// the merged level is made crease-true: sliver domains (few points, or points whose normals split
// across a crease) are absorbed point by point into the neighbour that fits each point best, and a
// point's weight in a domain whose plane turns away from the point's normal moves to the domains
// of that point that do face its way, so a quad's basis (its alpha) stops at its crease.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "domains/domains.h"

namespace qf {

struct MergeOptions {
  // Flatness: the surface variation lambda_min / (lambda0 + lambda1 + lambda2) of the domain's
  // Psi-weighted point distribution (thesis 3.2's curvature metric) must not exceed this.
  double max_variation = 0.01;
  double max_angle_degrees = 10.0;  // between the two domains' planes
  DomainOptions domains;            // tau for the overlaps and the neighbour graph
  // Slivers, after merging (measured on the octahedron and cube, 8k-64k points: at the levels that
  // merge into one domain per face, the other domains hold 3-40 points of mass against ~1000+ for
  // a face, and straddle its edges). A domain is a sliver when its Psi mass is below sliver_share
  // of its heaviest neighbour's, or below straddle_share of it while its points' normals split
  // (the length of their Psi-weighted mean normal is below cos(straddle_angle_degrees); one flat
  // face gives ~1, two faces at the octahedron's 70.5 degrees give at most cos(35 degrees)).
  double sliver_share = 0.1;
  double straddle_share = 0.3;
  double straddle_angle_degrees = 20.0;
  // Crease trimming: a point's weight in a domain whose plane normal is more than this from the
  // point's normal moves to the point's other domains within it (in proportion to their weights);
  // when none of its domains is within it, the point keeps its weights. Between a smooth surface's
  // spread inside one domain and the 70.5 degrees of the octahedron's (90 of the cube's) edges.
  double crease_angle_degrees = 35.0;
  // The merged domains' neighbour graph is taken before trimming, with this share instead of
  // domains.neighbor_share: two faces share only their crease band, under 5% of a face's points
  // at 64k points (the graph came out empty); 2% gives the solid's 12 edges on 34 of the 36
  // octahedron and cube samplings measured (8k-64k points, seeds 1-6), 1% adds vertex neighbours.
  double crease_neighbor_share = 0.02;
  bool crease_true = true;  // false: the thesis' plain merge (no absorbing, no trimming)
};

struct MergeReport {
  std::size_t merges = 0;
  std::size_t slivers = 0;        // domains absorbed by their neighbours
  std::size_t trimmed = 0;        // point weights moved off a domain across a crease
  std::size_t before = 0, after = 0;  // basis functions
  // The merged domains' neighbour graph (i < j, sorted, output numbering) as they touch before
  // crease trimming (crease_neighbor_share): trimmed faces no longer overlap, but stay neighbours
  // at their crease, and the overlap renderer blends a quad's neighbours before locking it.
  std::vector<std::array<std::uint32_t, 2>> edges;
};

// Returns Psi' = merged and cleaned Psi (n x after; columns numbered in order of their first
// member, absorbed columns removed). Rows keep summing to 1. `normals` (one per point, or empty)
// orient the planes, detect straddling slivers and trim creases; without them slivers are found by
// mass only, absorbed by distance to the neighbours' planes, and nothing is trimmed. The overlap of
// a merged domain with another is taken as the sum of its members' overlaps with it (points in
// three domains count more than once): it orders the merges. Deterministic (no threads).
SparseMatrix merge_domains(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                           const MergeOptions& options = {}, MergeReport* report = nullptr);
// The thesis' plain merge (crease_true off), for callers without normals (decompose's debug view).
SparseMatrix merge_domains(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const MergeOptions& options = {},
                           MergeReport* report = nullptr);

// Number of non-empty domains (quads a level delivers) of Psi under `options`.
std::size_t count_domains(const SparseMatrix& psi, const DomainOptions& options = {});

}  // namespace qf
