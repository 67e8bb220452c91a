// Edge-collapse LODs through meshoptimizer (see simplify.h).
#include "simplify/simplify.h"

#include <meshoptimizer.h>

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

}  // namespace

SimplifiedMesh simplify_mesh(const TriangleMesh& mesh, std::size_t target_triangles, SimplifyMethod method) {
  if (mesh.triangles.empty()) throw std::invalid_argument("simplify_mesh: a mesh without triangles");
  // 1. Collapse on the shared vertices, texture seams and material borders ignored: keeping them
  //    closed held the spider's legs (their many seams) at their triangles while its abdomen was
  //    collapsed away to meet the budget, and cut the silhouette's IoU at the 4x level from 0.81
  //    to 0.74. No error bound (the budget decides), so the target error is the whole extent.
  std::vector<unsigned> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const Triangle& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
  std::vector<unsigned> kept(indices.size());
  float relative_error = 0;
  // A budget above the mesh's own count keeps the mesh (simplifySloppy asserts against it).
  target_triangles = std::min(target_triangles, mesh.triangles.size());
  if (method == SimplifyMethod::kSloppy)
    kept.resize(meshopt_simplifySloppy(kept.data(), indices.data(), indices.size(), &mesh.positions[0].x, mesh.positions.size(),
                                       sizeof(Vec3f), target_triangles * 3, 1.0f, &relative_error));
  else
    kept.resize(meshopt_simplify(kept.data(), indices.data(), indices.size(), &mesh.positions[0].x, mesh.positions.size(),
                                 sizeof(Vec3f), target_triangles * 3, 1.0f, 0, &relative_error));
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
