// Loading what runtime_gl draws: a baked .glb (tinygltf, with the QF_impostor_level extension when
// present) and reference scenes made from an input point set or mesh.
#pragma once

#include <optional>
#include <string>

#include "core/types.h"
#include "runtime_gl/scene.h"

namespace qf::render {

// Reads a .glb or .gltf. With the extension, item k is the extension's quad k (its centre, normal
// and neighbours); without it every pair of triangles (or lone triangle) is an item with its own
// centroid and normal, and no neighbours. Throws InputError ("render.gltf.*") naming the file.
ImpostorScene load_gltf(const std::string& path);

// A point impostor (.glb with QF_point_impostor), or nothing when the file lacks the extension.
// Throws InputError ("render.gltf.*") for unreadable files and malformed point data.
std::optional<PointImpostorScene> load_point_impostor(const std::string& path);

// A vertex-clustering LOD (.glb written by `qf-bake cluster`: node extras cellWidth), or nothing
// for other files. Throws InputError ("render.gltf.*") for unreadable files.
std::optional<ClusterScene> load_cluster_lod(const std::string& path);

// A reference scene of a point set: radii estimated from the spacing where missing (as the baker
// does), normals estimated by the surface analysis where missing.
SplatScene splat_scene(PointSet points, const std::string& source = "");

// A reference scene of a triangle mesh (normals area-weighted where missing). `source` names the
// file in errors (InputError "render.points.empty" / "render.mesh.empty"), here and in splat_scene.
MeshScene mesh_scene(const TriangleMesh& mesh, const std::string& source = "");

}  // namespace qf::render
