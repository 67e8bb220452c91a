// Mesh LODs by edge collapse: meshoptimizer's simplifier (quadric error, topology-preserving),
// the peer the impostor levels are measured against and the mesh LODs a user may ship.
#pragma once

#include <cstddef>

#include "core/types.h"

namespace qf {

struct SimplifiedMesh {
  TriangleMesh mesh;   // the kept vertices (with their colours) and the new triangles
  double error = 0;    // meshoptimizer's reported error, model units (see simplify_mesh)
};

// Collapses edges until at most `target_triangles` remain (or no collapse keeps the topology:
// then fewer are removed; the result says how many are left), by meshoptimizer 1.2's
// simplifyWithAttributes: the input's normals and vertex colours weigh in the error beside the
// positions. Vertex colours and normals follow their vertices; vertices split at a crease (a
// flat-shaded input's) may be merged where that costs least (meshoptimizer's permissive mode),
// so hard edges stay hard unless the budget needs them. A mesh with materials or texture
// coordinates keeps its materials and textures: material borders and the texture seams of
// textured materials are kept, and each corner keeps the UV its vertex had in that triangle's
// material; a mesh without normals gets none (left to the writer). `error` then combines the
// positions' deviation with the normals' and colours' (weighted as positions). Deterministic.
// Throws std::invalid_argument on a mesh without triangles.
// kSloppy: meshoptimizer's simplifySloppy instead (vertices clustered on a grid, topology not
// kept: thin parts and separate pieces merge; each kept triangle takes its material and corner
// UVs from the input triangles around it), the peer of the fidelity league for assets where
// edge collapse stalls (issue 31).
enum class SimplifyMethod { kCollapse, kSloppy };
SimplifiedMesh simplify_mesh(const TriangleMesh& mesh, std::size_t target_triangles, SimplifyMethod method = SimplifyMethod::kCollapse);

// A texture at half its size (sides rounded up): each texel the mean of 2 x 2, colours weighted by
// alpha and averaged in linear light; `data` (metallic-roughness, occlusion: linear values, not
// colours) averages the bytes as they are.
TextureImage halve_texture(const TextureImage& texture, bool data = false);

// Halves each of the mesh's textures until its longer side is at most `max_side` texels (those the
// materials read only as metallic-roughness or occlusion as data).
void fit_textures(TriangleMesh& mesh, int max_side);


}  // namespace qf
