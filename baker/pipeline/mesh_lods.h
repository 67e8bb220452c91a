// The mesh LODs of one asset (pipeline/asset.h, bake_asset's steps 2 and 2'): a mesh input's
// simplified or clustered files, a point set's from its reconstructed surface. Not part of the
// asset's interface: asset.h declares what `qf-bake simplify` and `cluster` share.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "pipeline/asset.h"

namespace qf {

// 2. Mesh inputs: mesh LODs for near and middle distances beside the impostors (their manifest
// entry; null when none), their files appended to `files`.
// `smooth`: a mesh without normals of its own is drawn smooth (else flat, as glTF draws it).
nlohmann::json mesh_lod_outputs(const TriangleMesh& mesh, const AssetOptions& o, const std::string& stem,
                                std::vector<OutputFile>& files, bool smooth);

// 2'. Point-set inputs: the peer a scan user would pick, the surface reconstructed
// (reconstruct/reconstruct.h) and simplified as a mesh input's LODs are (their manifest entry, with
// the reconstruction's figures; null with other mesh LODs than simplify, or no surface: `warnings`
// says why).
nlohmann::json reconstructed_lod_outputs(const PointSet& points, const AssetOptions& o, const std::string& stem,
                                         std::vector<OutputFile>& files, std::vector<std::string>& warnings);

// The warning of mesh LODs whose simplifier stalled, from the asset's `manifest` (empty when they
// did not stall): mesh_lods' `stopped` (this mesh's triangles and budget), and where the bake
// measured the coarsest LOD (the stalled mesh) how far it holds and its figures beside the input's
// as drawn there. Call it after the measuring.
std::string stalled_lods_warning(const nlohmann::json& manifest);

}  // namespace qf
