// The names our glTF files and their readers share: the custom extensions (schemas/), and the
// extras and attribute beside them. The writer (gltf/glb.cpp), the runtime's loader
// (runtime_gl/loader.cpp) and qf-diff (tools/diff.cpp) take them from here, so that a rename
// cannot leave one of them behind. Header only: the renderer includes it without linking the baker.
#pragma once

namespace qf {

// Root extension of an impostor level (schemas/QF_impostor_level): the quads' domains, errors and
// neighbour graph, and the blend rule.
constexpr const char* kImpostorExtension = "QF_impostor_level";
// Root extension of a point impostor (schemas/QF_point_impostor): pixel size, point count, seed,
// switch distance.
constexpr const char* kPointExtension = "QF_point_impostor";
// A vertex-clustering LOD: its cell width (node 0's extras), and its thick lines' per-vertex width.
constexpr const char* kCellWidthExtra = "cellWidth";
constexpr const char* kThicknessAttribute = "_THICKNESS";
// A combined LOD file: MSFT_lod on the root node, its lower LODs' screen coverages in its extras.
constexpr const char* kLodExtension = "MSFT_lod";
constexpr const char* kScreenCoverageExtra = "MSFT_screencoverage";
// Impostor levels store normals, tangents and texture coordinates as normalized integers.
constexpr const char* kQuantizationExtension = "KHR_mesh_quantization";
// A texture whose image is KTX2 (Basis Universal): its extension names the image (issue 32).
constexpr const char* kBasisuExtension = "KHR_texture_basisu";
// A texture whose image is WebP: its extension names the image (issue 32).
constexpr const char* kWebpExtension = "EXT_texture_webp";

}  // namespace qf
