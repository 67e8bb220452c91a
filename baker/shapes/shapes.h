// Analytic sample shapes with known answers (flat faces, creases, constant curvature), sampled
// uniformly by area with a seeded generator: the test fixtures and the bundled sample.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"

namespace qf {

struct ShapeOptions {
  std::size_t points = 16000;  // the paper's figure 1 octahedron has 16,000 points
  std::uint64_t seed = 1;      // same seed, same points, on every platform
};

// Names accepted by generate_shape, with a one-line description each.
struct ShapeInfo {
  const char* name;
  const char* description;
};
const std::vector<ShapeInfo>& shape_catalog();

// Generates the named shape with positions, unit normals (outward), colours and radii (from
// local spacing). Throws UsageError for an unknown name or points == 0.
PointSet generate_shape(const std::string& name, const ShapeOptions& options = {});

// The octahedron, cube or sphere as a closed triangle mesh: each flat face (the sphere: each
// octahedron face, projected) split into subdivisions^2 triangles, wound counter-clockwise seen
// from outside, with vertex colours. Throws UsageError for other names or subdivisions < 1.
TriangleMesh generate_mesh(const std::string& name, int subdivisions);

}  // namespace qf
