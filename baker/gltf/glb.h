// One impostor level as a binary glTF 2.0 file (.glb): the domain primitives as textured quads,
// the atlas (colour + Psi as alpha, and normal maps) embedded as PNG, and the custom extension
// QF_impostor_level with what a custom runtime needs (gltf-notes.md; schemas/; its name and the
// other keys readers share in core/gltf_keys.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "clustering/clustering.h"
#include "core/gltf_keys.h"
#include "gltf/ktx2.h"
#include "gltf/webp.h"
#include "primitives/atlas.h"
#include "primitives/support.h"

namespace qf {

// What a level's .glb holds. quads[k] is drawn with atlas.tiles[k], over half_u[k] x half_v[k]
// (the texture's extent: whole texels, so a little over the support rectangle).
struct ImpostorLevel {
  std::size_t level = 0;                    // AMG level (0 = points)
  std::vector<SupportRect> quads;
  std::vector<float> half_u, half_v;
  Atlas atlas;
  std::vector<std::array<std::uint32_t, 2>> edges;  // neighbour graph between quads (indices into quads)
  float alpha_ref = 0.1f;                   // the lock-by-depth alpha test (paper 4, fig. 10)
  double alpha_exponent = 1;                // alpha = 1 - (1 - Psi)^e (primitives/texture.h); 1 = Psi
};

struct GltfOptions {
  // Material for engines without the extension: MASK. Measured with `qf-render eval` (engine path,
  // 26 views): BLEND leaves 73% of bunny00's pixels as holes at ~300 quads (engines draw one mesh
  // unsorted with depth writes, so transparent texels hide what is behind them) and 32% on the
  // octahedron. With alpha = Psi, MASK 0.1/0.2/0.3/0.5 left 0.4/1.8/7.6/40% holes (bunny), IoU best
  // at 0.2. Mesh inputs store alpha with exponent 2 (primitives/texture.h alpha_exponent), where
  // 0.3 cuts the seams at Psi 0.16 and the outer edges nearer the surface.
  std::string alpha_mode = "MASK";
  float alpha_cutoff = 0.2f;  // MASK only; mesh inputs 0.3 (pipeline/bake.h use_surface_edges)
  std::string generator = "quasiflat";
  // The impostor levels' textures (issue 32, docs/textures.md). PNG: every engine loads it, and
  // makes its mip levels itself by box filtering (an alpha-tested level loses coverage as it
  // shrinks). KTX2 (KHR_texture_basisu, then required): Basis Universal with the mip levels written
  // in, coverage-preserving at alpha_cutoff (primitives/mip_levels.h); engines need a transcoder.
  // WebP (EXT_texture_webp, then required): fewer file bytes than PNG, no mip levels, the same GPU
  // memory (decoded to RGBA8); three.js and Babylon.js load it without setup.
  enum class Textures { kPng, kKtx2, kWebp };
  Textures textures = Textures::kPng;
  BasisCodec color_codec = BasisCodec::kEtc1s;   // colour + alpha, emission
  BasisCodec normal_codec = BasisCodec::kUastc;  // normal maps and occlusion/roughness/metallic
  int etc1s_quality = 128;
  int threads = 1;  // the KTX2 encoder's (the bytes do not depend on it)
  // WebP settings by texture class (docs/textures.md, "WebP settings, by measurement"): colour +
  // alpha and emission; normal maps. Occlusion/roughness/metallic data is always lossless.
  WebpOptions webp_color = default_webp_color();
  WebpOptions webp_normal = default_webp_normal();
};
const char* textures_name(GltfOptions::Textures textures);         // "png" | "ktx2" | "webp"
GltfOptions::Textures parse_textures(const std::string& name);      // throws std::invalid_argument

// What a level's textures cost a user (issue 32): their bytes in the file, and the GPU memory
// they take once loaded, every mip level included (~4/3 of the base): PNG decoded to RGBA8, 4
// bytes a texel; KTX2 transcoded to a block format (BC7, ETC2 RGBA or ASTC 4x4), 16 bytes a 4x4
// block, 1 byte a texel.
struct TextureCost {
  std::size_t file_bytes = 0;
  std::size_t gpu_bytes = 0;
  std::size_t texels = 0;  // base-level texels of every image in the file, as an engine uploads them
};

// Assembles a level from its support rectangles and textures (one per non-empty domain, in domain
// order, as support_rectangles returns them): packs the atlas and maps the domains' neighbour
// graph onto quad indices.
ImpostorLevel make_impostor_level(std::size_t level, const std::vector<SupportRect>& rects,
                                  const std::vector<Texture>& textures, const Domains& domains,
                                  const AtlasOptions& atlas = {});

// The .glb bytes: identical for identical input (sorted keys, canonical floats, no timestamps).
// With `cost`, what its textures cost.
std::vector<std::uint8_t> encode_glb(const ImpostorLevel& level, const GltfOptions& options = {}, TextureCost* cost = nullptr);

// One .glb under MSFT_lod (gltf-notes.md 2.1) from finished .glb files (`parts`, finest or
// nearest first, each with one root node in its scene: any file the bake writes): the impostor
// levels of --lod-file, or the recommended chain's files. The parts' root nodes are named
// NAME_LOD0..n (the LOD-group suffix of Unity, Unreal and Godot); the first is the scene's only
// node and lists the others as lower LODs; screen_coverage (one per part, as
// MSFT_screencoverage) says down to which fraction of the screen height each is shown. Plain glTF
// plus MSFT_lod: the parts' own document extensions (QF_impostor_level, QF_point_impostor) are
// left out, a custom runtime reads the per-level files. Throws std::invalid_argument for a part
// it cannot combine.
std::vector<std::uint8_t> combine_lod_glb(const std::vector<const std::vector<std::uint8_t>*>& parts,
                                          const std::vector<double>& screen_coverage, const std::string& name);

// The bytes of a finished .glb's images (its textures as stored, every format). Throws
// std::invalid_argument where combine_lod_glb would.
std::size_t glb_image_bytes(const std::vector<std::uint8_t>& glb);

// One .glb drawing every part at once (`parts`: finished .glb files as for combine_lod_glb; the
// tiles of one scan, qf-bake join): a root node NAME whose children are the parts' root nodes,
// named NAME_0..n (or part_names, one per part, where given: an assembly's bodies), their
// materials and textures prefixed the same way. Plain glTF, as combine_lod_glb's: the parts'
// document extensions are left out. Throws std::invalid_argument for a part it cannot combine.
std::vector<std::uint8_t> join_glb(const std::vector<const std::vector<std::uint8_t>*>& parts, const std::string& name,
                                   const std::vector<std::string>& part_names = {});

// A point impostor (paper section 5): the permuted sample points as one glTF POINTS primitive
// (POSITION, NORMAL, COLOR_0 when coloured; the order is the permutation, so any prefix is an even
// thinning) and the root extension QF_point_impostor: the LDI pixel side s, the point count N0,
// the seed, and the distance at which a runtime switches to the mesh on a reference screen
// (N = N0 (s Z0 / d)^2 points at distance d, Z0 = H / (2 tan(fov / 2)); all N0 at d = s Z0).
struct PointImpostorInfo {
  float pixel = 0;         // s, model units
  std::uint64_t seed = 1;  // of the permutation
  int reference_height = 1080;     // screen height, pixels, of switchDistance
  float reference_fov_degrees = 60;  // vertical field of view of switchDistance
};
std::vector<std::uint8_t> encode_point_glb(const PointSet& permuted_points, const PointImpostorInfo& info,
                                           const GltfOptions& options = {});
double point_switch_distance(const PointImpostorInfo& info);  // s Z0 on the reference screen

// A vertex-clustering LOD mesh (seed 002): its triangles (smooth area-weighted normals, double
// sided: clustering does not keep orientation), thick edges as a LINES primitive with the custom
// per-vertex attribute _THICKNESS (model units; a runtime draws width = thickness / R pixels), and
// isolated points as POINTS; COLOR_0 (16-bit linear) where the mesh has colours. The node's extras
// give the cell width. With `draco`, the triangles are a KHR_draco_mesh_compression primitive with no
// uncompressed fallback (the extension is then required; lines and points stay plain).
std::vector<std::uint8_t> encode_cluster_glb(const LodMesh& lod, const GltfOptions& options = {}, bool draco = false);

// A plain triangle mesh (an edge-collapse LOD): indexed triangles, NORMALs: the mesh's own where it
// has them, else smooth area-weighted ones when `smooth_normals` (else none: engines then shade each
// triangle flat), COLOR_0 (16-bit linear) where the mesh has colours.
std::vector<std::uint8_t> encode_mesh_glb(const TriangleMesh& mesh, bool smooth_normals, const GltfOptions& options = {});

// A mesh with its materials as a game asset (qf-bake generate tree, a textured mesh LOD): one
// primitive per material, with its base colour factor, texture, sampler wraps, alpha mode,
// sidedness and its metallic, roughness, emissive and occlusion factors and textures (sharing the
// base colour's uvs); corners that share a position and texture coordinate share a vertex. Textures
// PNG, or KTX2 with options.textures kKtx2 (the levels' codecs and mip levels; KHR_texture_basisu
// then required); `cost` (when given) adds their bytes, texels and GPU memory. Same mesh, same bytes.
std::vector<std::uint8_t> encode_textured_mesh_glb(const TriangleMesh& mesh, const GltfOptions& options = {}, TextureCost* cost = nullptr);

}  // namespace qf
