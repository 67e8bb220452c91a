// Support rectangles of the domains (paper 3.1; thesis 3.1-3.2): the plane and bounding rectangle
// that a domain primitive's textured quad lies on, and how far the domain's points are from it.
#pragma once

#include <cstdint>
#include <vector>

#include "core/sparse.h"
#include "core/types.h"
#include "domains/domains.h"

namespace qf {

struct SupportOptions {
  bool weighted = true;          // PCA weighted by Psi (paper); false = every domain point counts the same
  bool projected_radii = false;  // splat extent r' = |n_p . n| r instead of r (thesis 3.1)
  float margin = 0.0f;           // added around the rectangle, in units of the domain's mean point radius
};

// A rectangle in 3D: centre + s * axis_u + t * axis_v, |s| <= half_u, |t| <= half_v; (axis_u,
// axis_v, normal) is a right-handed orthonormal frame, axis_u the in-plane direction of largest
// spread. Errors are over the domain's points.
struct SupportRect {
  std::uint32_t domain = 0;     // column of Psi
  std::uint32_t points = 0;     // points in the domain
  Vec3f center, normal, axis_u, axis_v;
  float half_u = 0, half_v = 0;
  float mean_radius = 0;        // of the domain's points, world units
  double error = 0;             // mean |distance to the plane|, world units
  double relative_error = 0;    // error / mean_radius (thesis table 5.2)
};

// One rectangle per non-empty domain, in domain order. `normals` (one per point, may be empty)
// orient each plane's normal to agree with the domain's weighted mean normal; without them the
// normal points away from the centroid of all points. `radii` must have one entry per point.
// Degenerate domains (one point, collinear points) get the plane of their mean normal.
std::vector<SupportRect> support_rectangles(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                            const std::vector<float>& radii, const SparseMatrix& psi,
                                            const Domains& domains, const SupportOptions& options = {});

}  // namespace qf
