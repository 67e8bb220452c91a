// Mesh LODs by edge collapse: meshoptimizer's simplifier (quadric error, topology-preserving),
// the peer the impostor levels are measured against and the mesh LODs a user may ship.
#pragma once

#include <cstddef>

#include "core/types.h"

namespace qf {

struct SimplifiedMesh {
  TriangleMesh mesh;   // the kept vertices (with their colours) and the new triangles
  double error = 0;    // meshoptimizer's reported deviation, model units
};

// Collapses edges until at most `target_triangles` remain (or no collapse keeps the topology:
// then fewer are removed; the result says how many are left). Vertex colours follow their
// vertices; normals are left to the writer. Deterministic. Throws std::invalid_argument on a
// mesh without triangles.
SimplifiedMesh simplify_mesh(const TriangleMesh& mesh, std::size_t target_triangles);

}  // namespace qf
