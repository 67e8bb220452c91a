// Which sampled points of a mesh an outside view can see (issue 31, "only what can be seen"). Depth
// peeling finds every layer, the inside of a closed housing and the parts inside it too; those
// surfaces would colour the quads of the shell around them (2CylinderEngine's pistons speckled its
// housing) and spend the decomposition's functions on what no camera shows.
#pragma once

#include <cstdint>
#include <vector>

#include "core/types.h"

namespace qf {

struct VisibilityOptions {
  // Directions the mesh is looked at from, spread evenly over the sphere (a Fibonacci lattice);
  // 0 keeps every point. 48 leaves about 17 degrees between neighbouring directions, so a point of
  // a convex region is seen from within 17 degrees of its normal.
  int views = 48;
  // Pixels across the bounding sphere per view: about the sampling's pixel (so the depth test's
  // tolerance scales with it), at most this many.
  int max_resolution = 1024;
};

// Per point (0/1): 1 where the point lies on the nearest opaque surface, to within `tolerance`
// (model units; the sampling's pixel), of at least one orthographic view from outside the
// bounding sphere. Depth test against the farthest of the nearest depths in the 3 x 3 pixels
// around the point, so points on a silhouette or a grazing surface count as seen. Triangles with a
// MASK or BLEND material occlude nothing (light passes their cut-outs); degenerate and sub-pixel
// triangles neither. `pixel` sets the views' resolution (2 x sphere radius / pixel, capped).
// The same points and mesh give the same flags at any thread count.
std::vector<char> visible_points(const TriangleMesh& mesh, const std::vector<Vec3f>& positions, float pixel,
                                 const VisibilityOptions& options = {});

}  // namespace qf
