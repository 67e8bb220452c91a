// Edge-collapse LODs through meshoptimizer (see simplify.h).
#include "simplify/simplify.h"

#include <meshoptimizer.h>

// meshopt_simplifyWithAttributes, meshopt_SimplifyPermissive and the vertex flags are 1.x API: the
// project's copy (third_party/meshoptimizer), never Debian's 0.18 header.
static_assert(MESHOPTIMIZER_VERSION >= 1020, "simplify.cpp needs meshoptimizer 1.2 (third_party/meshoptimizer)");

#include "core/color.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <map>
#include <stdexcept>
#include <tuple>

namespace qf {
namespace {

// The corners of the input's triangles at each vertex: (triangle, corner) pairs.
std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>> corners_at(const TriangleMesh& mesh) {
  std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>> at(mesh.positions.size());
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint8_t k = 0; k < 3; ++k) at[mesh.triangles[t][k]].push_back({t, k});
  return at;
}

// A kept triangle's material and corner UVs, from the input triangles around its corners: the
// material of the input triangle sharing most of its corners (the lowest-numbered among ties); each
// corner's UV from that triangle where it is one of its corners, else the corner's UV (in that
// material) nearest that triangle's mean UV, so that a corner on a texture seam takes the side the
// rest of the triangle lies on.
void transfer_surface(const TriangleMesh& mesh, const std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>>& at,
                      const Triangle& kept, std::array<Vec2f, 3>& uv, std::uint32_t& material) {
  std::uint32_t best = 0;
  int best_shared = -1;
  for (std::uint32_t v : kept)
    for (const auto& [t, k] : at[v]) {
      int shared = 0;
      for (std::uint32_t w : mesh.triangles[t]) shared += w == kept[0] || w == kept[1] || w == kept[2];
      if (shared > best_shared || (shared == best_shared && t < best)) best_shared = shared, best = t;
    }
  material = mesh.triangle_materials.empty() ? 0 : mesh.triangle_materials[best];
  if (mesh.corner_uvs.empty()) return;
  const std::array<Vec2f, 3>& own = mesh.corner_uvs[best];
  const Vec2f mean{(own[0].x + own[1].x + own[2].x) / 3, (own[0].y + own[1].y + own[2].y) / 3};
  for (std::size_t c = 0; c < 3; ++c) {
    double nearest = INFINITY;
    for (std::size_t k = 0; k < 3; ++k)
      if (mesh.triangles[best][k] == kept[c]) uv[c] = own[k], nearest = -1;
    for (const auto& [t, k] : at[kept[c]]) {
      if (nearest < 0) break;
      if (!mesh.triangle_materials.empty() && mesh.triangle_materials[t] != material) continue;
      const Vec2f w = mesh.corner_uvs[t][k];
      const double d = std::hypot(w.x - mean.x, w.y - mean.y);
      if (d < nearest) nearest = d, uv[c] = w;
    }
    if (nearest == INFINITY) uv[c] = mesh.corner_uvs[at[kept[c]][0].first][at[kept[c]][0].second];
  }
}


// How much the normals weigh against positions in the collapse's error (meshoptimizer: a change of
// 1/weight in a normal over a distance d costs about what moving a vertex by d does). Measured
// (engine method, 8 views, 128 px) against positions alone: 0.1 kept or raised PSNR on the
// spider, the oak and Wuson, at most 0.035 of IoU lost (Wuson's 58 triangles); 0.25 and 0.5
// (gltfpack's) lost silhouette where the budget went to shading (Wuson 0.81 -> 0.73 IoU at 58,
// the bare tree 0.85 -> 0.78 at 211); 1.0 less still.
constexpr float kNormalWeight = 0.1f;
// Vertex colours in linear light, weighted as meshoptimizer's guide does for normalized colours.
constexpr float kColorWeight = 1.0f;

// Whether a material reads the texture coordinates (any of its textures).
bool reads_uvs(const SurfaceMaterial& m) {
  return m.texture >= 0 || m.metallic_roughness.image >= 0 || m.emissive_texture.image >= 0 || m.occlusion.image >= 0;
}

// The corners as meshoptimizer wants them: a vertex of their own where an input vertex carries
// several materials, or several texture coordinates under a textured material (those under an
// untextured one are never seen, so they split nothing: Wuson's UV seams held collapses for no
// look). Numbered in first-use order, so the same input gives the same numbering.
struct SplitMesh {
  std::vector<std::uint32_t> source;    // the input vertex of each split vertex
  std::vector<Vec2f> uv;                // its texture coordinates (its first corner's where untextured)
  std::vector<std::uint32_t> material;  // its material (0 without materials)
  std::vector<unsigned> indices;        // three a triangle, into the split vertices
};

SplitMesh split_corners(const TriangleMesh& mesh) {
  SplitMesh out;
  std::map<std::tuple<std::uint32_t, std::uint32_t, float, float>, unsigned> seen;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[t][k];
      const std::uint32_t m = mesh.triangle_materials.empty() ? 0 : mesh.triangle_materials[t];
      const Vec2f uv = mesh.corner_uvs.empty() ? Vec2f{} : mesh.corner_uvs[t][k];
      const bool seen_uv = m < mesh.materials.size() && reads_uvs(mesh.materials[m]);
      const auto [it, added] = seen.insert({{v, m, seen_uv ? uv.x : 0.0f, seen_uv ? uv.y : 0.0f}, static_cast<unsigned>(out.source.size())});
      if (added) out.source.push_back(v), out.uv.push_back(uv), out.material.push_back(m);
      out.indices.push_back(it->second);
    }
  return out;
}

// Per split vertex: its normal (3) and linear colour (3), and the weights (zero for what the mesh
// lacks). Texture coordinates stay out of the error: weighted in (1/sqrt of the mean UV area,
// meshoptimizer's guide), they cost the spider 0.6 dB and 0.02 IoU at 342 triangles; the seams
// below keep them instead.
constexpr std::size_t kAttributes = 6;
std::vector<float> vertex_attributes(const TriangleMesh& mesh, const SplitMesh& split, float (&weights)[kAttributes]) {
  const bool normals = mesh.normals.size() == mesh.positions.size(), colors = mesh.colors.size() == mesh.positions.size();
  std::vector<float> a(split.source.size() * kAttributes, 0.0f);
  for (std::size_t i = 0; i < split.source.size(); ++i) {
    const std::uint32_t v = split.source[i];
    float* p = &a[i * kAttributes];
    if (normals) p[0] = mesh.normals[v].x, p[1] = mesh.normals[v].y, p[2] = mesh.normals[v].z;
    if (colors) p[3] = srgb8_to_linear(mesh.colors[v].r), p[4] = srgb8_to_linear(mesh.colors[v].g), p[5] = srgb8_to_linear(mesh.colors[v].b);
  }
  for (std::size_t k = 0; k < 3; ++k) weights[k] = normals ? kNormalWeight : 0.0f, weights[3 + k] = colors ? kColorWeight : 0.0f;
  return a;
}

// meshopt_SimplifyVertex_Protect on the copies of a position that differ in material or seen
// texture coordinates: permissive collapse may cross normal seams (creases), never these.
std::vector<unsigned char> protect_seams(const std::vector<Vec3f>& positions, const SplitMesh& split, const TriangleMesh& mesh) {
  std::vector<unsigned> first(positions.size());
  meshopt_generatePositionRemap(first.data(), &positions[0].x, positions.size(), sizeof(Vec3f));
  std::vector<unsigned char> flags(positions.size(), 0);
  const auto seen_uv = [&](unsigned i) { return split.material[i] < mesh.materials.size() && reads_uvs(mesh.materials[split.material[i]]); };
  for (unsigned i = 0; i < positions.size(); ++i) {
    const unsigned r = first[i];
    const bool uv_differs = (seen_uv(i) || seen_uv(r)) && (split.uv[i].x != split.uv[r].x || split.uv[i].y != split.uv[r].y);
    if (r != i && (split.material[i] != split.material[r] || uv_differs)) flags[i] = meshopt_SimplifyVertex_Protect;
  }
  return flags;
}

// The kept triangles over the split vertices as a mesh: the used vertices in first-use order with
// their input's normals and colours, each corner its split vertex's UV, each triangle the material
// of its corners (of the last two where they differ).
TriangleMesh kept_mesh(const TriangleMesh& mesh, const SplitMesh& split, const std::vector<unsigned>& kept) {
  std::vector<unsigned> remap(split.source.size());
  const std::size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), kept.data(), kept.size(), split.source.size());
  TriangleMesh out;
  out.positions.resize(used);
  if (mesh.colors.size() == mesh.positions.size()) out.colors.resize(used);
  if (mesh.normals.size() == mesh.positions.size()) out.normals.resize(used);
  for (std::size_t i = 0; i < split.source.size(); ++i) {
    if (remap[i] == ~0u) continue;
    const std::uint32_t v = split.source[i];
    out.positions[remap[i]] = mesh.positions[v];
    if (!out.colors.empty()) out.colors[remap[i]] = mesh.colors[v];
    if (!out.normals.empty()) out.normals[remap[i]] = mesh.normals[v];
  }
  for (std::size_t i = 0; i + 2 < kept.size(); i += 3) {
    out.triangles.push_back({remap[kept[i]], remap[kept[i + 1]], remap[kept[i + 2]]});
    if (!mesh.corner_uvs.empty()) out.corner_uvs.push_back({split.uv[kept[i]], split.uv[kept[i + 1]], split.uv[kept[i + 2]]});
    const std::uint32_t b = split.material[kept[i + 1]], c = split.material[kept[i + 2]];
    if (!mesh.triangle_materials.empty()) out.triangle_materials.push_back(b == c ? b : split.material[kept[i]]);
  }
  out.materials = mesh.materials;
  out.textures = mesh.textures;
  return out;
}

// Edge collapse with the normals and colours in the error, materials and seen UV seams kept,
// normal seams crossed where that costs least (meshopt_SimplifyPermissive: 2CylinderEngine's
// creases stalled it at 33,008 triangles with 0.18, at 21,597 with 1.2 without it).
SimplifiedMesh collapse(const TriangleMesh& mesh, std::size_t target_triangles) {
  const SplitMesh split = split_corners(mesh);
  std::vector<Vec3f> positions(split.source.size());
  for (std::size_t i = 0; i < positions.size(); ++i) positions[i] = mesh.positions[split.source[i]];
  float weights[kAttributes];
  const std::vector<float> attributes = vertex_attributes(mesh, split, weights);
  const std::vector<unsigned char> flags = protect_seams(positions, split, mesh);
  // No error bound (the budget decides), so the target error is the whole extent. No
  // meshopt_SimplifyPrune: with that bound it removed the lattice's every beam at 225 triangles.
  std::vector<unsigned> kept(split.indices.size());
  float relative_error = 0;
  kept.resize(meshopt_simplifyWithAttributes(kept.data(), split.indices.data(), split.indices.size(), &positions[0].x, positions.size(),
                                             sizeof(Vec3f), attributes.data(), kAttributes * sizeof(float), weights, kAttributes,
                                             flags.data(), target_triangles * 3, 1.0f, meshopt_SimplifyPermissive, &relative_error));
  SimplifiedMesh out;
  out.mesh = kept_mesh(mesh, split, kept);
  out.error = relative_error * meshopt_simplifyScale(&positions[0].x, positions.size(), sizeof(Vec3f));
  return out;
}

}  // namespace

SimplifiedMesh simplify_mesh(const TriangleMesh& mesh, std::size_t target_triangles, SimplifyMethod method) {
  if (mesh.triangles.empty()) throw std::invalid_argument("simplify_mesh: a mesh without triangles");
  // A budget above the mesh's own count keeps the mesh (simplifySloppy asserts against it).
  target_triangles = std::min(target_triangles, mesh.triangles.size());
  if (method == SimplifyMethod::kCollapse) return collapse(mesh, target_triangles);
  // 1. simplifySloppy on the shared vertices (no error bound: the budget decides).
  std::vector<unsigned> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const Triangle& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
  std::vector<unsigned> kept(indices.size());
  float relative_error = 0;
  kept.resize(meshopt_simplifySloppy(kept.data(), indices.data(), indices.size(), &mesh.positions[0].x, mesh.positions.size(),
                                     sizeof(Vec3f), nullptr, target_triangles * 3, 1.0f, &relative_error));
  // 2. Keep only the vertices still used (with their colours and normals: a flat-shaded input has
  //    its vertices split at each crease, which meshoptimizer keeps as seams, so the kept corners
  //    keep the input's hard edges), in first-use order (meshopt_optimizeVertexFetch's order).
  std::vector<unsigned> remap(mesh.positions.size());
  const std::size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), kept.data(), kept.size(), mesh.positions.size());
  SimplifiedMesh out;
  out.mesh.positions.resize(used);
  if (mesh.colors.size() == mesh.positions.size()) out.mesh.colors.resize(used);
  if (mesh.normals.size() == mesh.positions.size()) out.mesh.normals.resize(used);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (remap[v] == ~0u) continue;
    out.mesh.positions[remap[v]] = mesh.positions[v];
    if (!out.mesh.colors.empty()) out.mesh.colors[remap[v]] = mesh.colors[v];
    if (!out.mesh.normals.empty()) out.mesh.normals[remap[v]] = mesh.normals[v];
  }
  // 3. The triangles, with materials and texture coordinates taken over from the input's.
  const bool surface = !mesh.corner_uvs.empty() || !mesh.triangle_materials.empty();
  const auto at = surface ? corners_at(mesh) : std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>>{};
  for (std::size_t i = 0; i + 2 < kept.size(); i += 3) {
    out.mesh.triangles.push_back({remap[kept[i]], remap[kept[i + 1]], remap[kept[i + 2]]});
    if (!surface) continue;
    std::array<Vec2f, 3> uv{};
    std::uint32_t material = 0;
    transfer_surface(mesh, at, {kept[i], kept[i + 1], kept[i + 2]}, uv, material);
    if (!mesh.corner_uvs.empty()) out.mesh.corner_uvs.push_back(uv);
    if (!mesh.triangle_materials.empty()) out.mesh.triangle_materials.push_back(material);
  }
  out.mesh.materials = mesh.materials;
  out.mesh.textures = mesh.textures;
  out.error = relative_error * meshopt_simplifyScale(&mesh.positions[0].x, mesh.positions.size(), sizeof(Vec3f));
  return out;
}

TextureImage halve_texture(const TextureImage& t, bool data) {
  TextureImage h;
  h.width = std::max(1, (t.width + 1) / 2), h.height = std::max(1, (t.height + 1) / 2);
  h.rgba.resize(4 * static_cast<std::size_t>(h.width) * static_cast<std::size_t>(h.height));
  for (int j = 0; j < h.height; ++j)
    for (int i = 0; i < h.width; ++i) {
      // The 2 x 2 texels (the last row or column repeated on odd sides), colour weighted by alpha
      // and averaged in linear light, as a GPU's mipmap filter would.
      double sum[3] = {0, 0, 0}, alpha = 0;
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
          const std::size_t x = static_cast<std::size_t>(std::min(2 * i + di, t.width - 1));
          const std::size_t y = static_cast<std::size_t>(std::min(2 * j + dj, t.height - 1));
          const std::uint8_t* p = &t.rgba[4 * (y * static_cast<std::size_t>(t.width) + x)];
          const double a = p[3] / 255.0;
          for (int c = 0; c < 3; ++c) sum[c] += a * (data ? p[c] / 255.0 : srgb8_to_linear(p[c]));
          alpha += a;
        }
      std::uint8_t* q = &h.rgba[4 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(h.width) + static_cast<std::size_t>(i))];
      for (int c = 0; c < 3; ++c)
        q[c] = alpha > 0 ? (data ? static_cast<std::uint8_t>(std::lround(std::clamp(sum[c] / alpha, 0.0, 1.0) * 255)) : linear_to_srgb8(sum[c] / alpha)) : 0;
      q[3] = static_cast<std::uint8_t>(std::lround(alpha / 4 * 255));
    }
  return h;
}

void fit_textures(TriangleMesh& mesh, int max_side) {
  // Data textures: read as metallic-roughness or occlusion and never as a colour.
  std::vector<char> data(mesh.textures.size(), 0);
  for (const SurfaceMaterial& m : mesh.materials)
    for (int i : {m.metallic_roughness.image, m.occlusion.image})
      if (i >= 0) data[static_cast<std::size_t>(i)] = 1;
  for (const SurfaceMaterial& m : mesh.materials)
    for (int i : {m.texture, m.emissive_texture.image})
      if (i >= 0) data[static_cast<std::size_t>(i)] = 0;
  for (std::size_t k = 0; k < mesh.textures.size(); ++k)
    while (std::max(mesh.textures[k].width, mesh.textures[k].height) > std::max(1, max_side))
      mesh.textures[k] = halve_texture(mesh.textures[k], data[k] != 0);
}

}  // namespace qf
