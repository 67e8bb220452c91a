// Local frames and the moment-based surface classifier (paper 2.1, eqs. 1-3; thesis 2.3).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "analysis/neighborhoods.h"
#include "core/types.h"

namespace qf {

// Per point: the zero moment M0 (barycentre of the point and its neighbours), the first moment
// M1 (their covariance around M0), its eigenvalues lambda0 >= lambda1 >= lambda2 >= 0 (world
// units squared) and eigenvectors: e0, e1 span the tangent plane, normal = e2 (oriented once
// orient_normals has run; flipped and components count from then).
struct LocalFrames {
  std::vector<std::array<float, 3>> eigenvalues;  // lambda0, lambda1, lambda2
  std::vector<Vec3f> e0, e1, normal;              // unit vectors; (e0, e1, normal) right-handed
  std::vector<float> centroid_offset;             // |M0 - x|, world units
  std::vector<float> radius;                      // distance to the farthest neighbour (0 if none)
  std::size_t flipped = 0;     // normals turned around by the orientation step
  std::size_t components = 0;  // connected parts of the neighbour graph oriented separately
  std::size_t isolated = 0;    // points without neighbours (frame = world axes)
};

// Frames from neighbourhoods, their normals not yet oriented (each e2 as the eigen-solver gives
// it). Uses every core; the result does not depend on the thread count.
LocalFrames compute_local_frames(const std::vector<Vec3f>& positions, const Neighborhoods& nb);

// Orients the frames' normals (e1 turns with them, so the frames stay right-handed): by
// `input_normals` where given (one per point: e2 is turned to agree with it); otherwise
// consistently by propagation over the neighbour graph (minimum spanning tree on
// 1 - |n_i . n_j|, Hoppe et al. 1992), each connected part seeded at its point farthest from the
// part's centroid with a normal pointing away from it, which makes closed surfaces outward. The
// propagation is serial.
void orient_normals(const std::vector<Vec3f>& positions, const Neighborhoods& nb, const std::vector<Vec3f>* input_normals,
                    LocalFrames& frames);

enum class ClassifierKind { kPaper, kVariation };

struct ClassifierOptions {
  ClassifierKind kind = ClassifierKind::kPaper;
  float alpha = 0.01f;   // G(s) = 1 / (alpha + beta s^2), paper eq. 3
  float beta = 100.0f;
  float epsilon = 0.0f;  // feature size eps of eq. 3 (world units); 0 = use each point's local
                         // sample spacing (see classify), which makes C scale-free
};

struct Classifier {
  std::vector<float> value;      // the diffusion coefficient C used by the stiffness matrix, > 0
  std::vector<float> variation;  // surface variation sigma = lambda2 / (lambda0 + lambda1 + lambda2), in [0, 1/3]
};

// Paper (default): C = G(|M0 - x| lambda2 / (eps lambda0)), eq. 3. With epsilon off, eps is a
// quarter of the point's sample spacing h (h = mean distance to its 6 nearest neighbours), so s
// compares the barycentre shift with the spacing and is unchanged by uniform scaling. On a flat
// area s = 0 and C = 1/alpha = 100; at the octahedron's edges (k = 50) C is ~1/1000 of that, the
// "several orders of magnitude" of the paper. Why a quarter: eps = h gives only ~1/66 and the
// neighbourhood radius ~1/6; with h/2 (~1/260) AMG still merges functions across the octahedron's
// edges at its coarse levels, with h/4 it keeps one face per function down to 16 functions
// (amg-notes 3.5: crease couplings must be ~1e-3 of the others).
// Variation (thesis 2.3): C = G(3 sigma), 3 sigma in [0, 1] taking the role of s.
// Both stay finite for degenerate neighbourhoods (lambda0 = 0 gives s = 0).
Classifier classify(const LocalFrames& frames, const Neighborhoods& nb, const ClassifierOptions& options = {});

}  // namespace qf
