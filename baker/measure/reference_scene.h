// Reference scenes: an input point set or mesh (the baker's readers' types) made ready for the
// renderer, to compare a bake against what it was baked from. Outside runtime_gl because it needs
// the baker: radii and normals of bare point sets are estimated by the baker's own analysis, so the
// reference is lit as the bake was made.
#pragma once

#include <string>

#include "core/types.h"
#include "runtime_gl/engine_scene.h"
#include "runtime_gl/scene.h"

namespace qf::render {

// A reference scene of a point set: radii estimated from the spacing where missing (as the baker
// does), normals estimated by the surface analysis where missing.
SplatScene splat_scene(PointSet points, const std::string& source = "");

// A reference scene of a triangle mesh (normals area-weighted where missing). `source` names the
// file in errors (InputError "render.points.empty" / "render.mesh.empty"), here and in splat_scene.
MeshScene mesh_scene(const TriangleMesh& mesh, const std::string& source = "");

// A reference mesh as an engine draws it: vertex normals and colours (COLOR_0, linear) with a
// rough dielectric, double-sided material (an input mesh carries no material of its own).
EngineScene engine_scene(const MeshScene& mesh);
// True when `mesh` has a look of its own that only materials carry (glTF, OBJ + MTL with a texture
// or a base colour; or metallic, roughness, occlusion or emission other than a rough dielectric's):
// the sampler's test of colour (sample.cpp), so the reference shows what the bake's points were
// coloured with, and a mesh without one keeps the constant base colour.
bool has_material_look(const TriangleMesh& mesh);
// A mesh as an engine draws it had it been exported as glTF with its materials: one primitive per
// material used (in material order), vertices unshared (three per triangle: the corner UVs split
// what positions share) with `scene`'s normals, the corner UVs and the vertex colours as COLOR_0
// (linear; absent when the mesh has none, so the material's colour shows), the textures as images,
// each material's base colour factor, wraps, alpha mode and its other channels. Meshes without a material look
// (has_material_look false) give engine_scene(scene), unchanged. `scene` = mesh_scene(mesh).
EngineScene engine_scene(const TriangleMesh& mesh, const MeshScene& scene);
// A reference point set: each splat a disc (a quad with a disc alpha texture, MASK 0.5), facing
// its normal, in its colour, with the same material as meshes.
EngineScene engine_scene(const SplatScene& splats);

}  // namespace qf::render
