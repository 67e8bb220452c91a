// Reference scenes of input point sets and meshes, for the GL 1.1 methods and as an engine draws
// them (see reference_scene.h).
#include "measure/reference_scene.h"

#include <algorithm>
#include <cmath>

#include "analysis/local_frames.h"
#include "analysis/neighborhoods.h"
#include "core/color.h"
#include "core/error.h"

namespace qf::render {
namespace {

// What an exported input mesh or point set would carry: a rough dielectric seen from both sides.
EngineMaterial reference_material() {
  EngineMaterial m;
  m.metallic = 0;
  m.roughness = 1;
  m.double_sided = true;
  return m;
}

void push_linear(std::vector<float>& out, Rgb8 c) {
  for (std::uint8_t v : {c.r, c.g, c.b}) out.push_back(srgb_to_linear16(v) / 65535.0f);
  out.push_back(1.0f);
}

// The splat footprint: a disc whose edge crosses alpha 0.5 at radius 1 under bilinear filtering
// (as the fixed-function splats of draw_gl11).
Image disc_image() {
  constexpr int kSide = 32;
  Image img{kSide, kSide, std::vector<std::uint8_t>(kSide * kSide * 4, 255)};
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const float u = (x + 0.5f) / kSide * 2 - 1, v = (y + 0.5f) / kSide * 2 - 1;
      const float r = std::sqrt(u * u + v * v);
      img.rgba[static_cast<std::size_t>(y * kSide + x) * 4 + 3] =
          static_cast<std::uint8_t>(std::clamp(0.5f + (1 - r) * kSide * 0.5f, 0.0f, 1.0f) * 255);
    }
  return img;
}

int wrap_code(TextureWrap w) {
  return w == TextureWrap::kClampToEdge ? 33071 : w == TextureWrap::kMirroredRepeat ? 33648 : 10497;
}

// A surface material as an engine material: double-sided (an input's winding is not trusted) with
// the file's colour, texture, wraps, alpha, and its metallic, roughness, occlusion and emission
// (SurfaceMaterial's defaults are the reference's rough dielectric).
EngineMaterial engine_material(const SurfaceMaterial& m) {
  EngineMaterial e = reference_material();
  e.metallic = m.metallic;
  e.roughness = m.roughness;
  e.metal_rough_texture = m.metallic_roughness.image;
  e.metal_rough_wrap_s = wrap_code(m.metallic_roughness.wrap_s), e.metal_rough_wrap_t = wrap_code(m.metallic_roughness.wrap_t);
  e.occlusion_texture = m.occlusion.image;
  e.occlusion_wrap_s = wrap_code(m.occlusion.wrap_s), e.occlusion_wrap_t = wrap_code(m.occlusion.wrap_t);
  e.occlusion_strength = m.occlusion_strength;
  e.emissive = m.emissive;
  e.emissive_texture = m.emissive_texture.image;
  e.emissive_wrap_s = wrap_code(m.emissive_texture.wrap_s), e.emissive_wrap_t = wrap_code(m.emissive_texture.wrap_t);
  e.base_color = m.base_color;
  e.base_texture = m.texture;
  e.base_wrap_s = wrap_code(m.wrap_s);
  e.base_wrap_t = wrap_code(m.wrap_t);
  e.alpha = m.alpha_mode == AlphaMode::kMask ? EngineMaterial::Alpha::kMask
            : m.alpha_mode == AlphaMode::kBlend ? EngineMaterial::Alpha::kBlend
                                                : EngineMaterial::Alpha::kOpaque;
  e.alpha_cutoff = m.alpha_cutoff;
  return e;
}

// Triangle t's three corners appended to p as unshared vertices; `uncoloured`: the mesh has no
// colour of its own (only other material channels), so its vertices take the scene's constant
// colour, as its quads do (surface_paint.h).
void push_corners(EnginePrimitive& p, const TriangleMesh& mesh, const MeshScene& scene, std::size_t t, bool uncoloured) {
  const Triangle& tri = mesh.triangles[t];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = tri[static_cast<std::size_t>(k)];
    p.indices.push_back(static_cast<std::uint32_t>(p.positions.size() / 3));
    p.positions.insert(p.positions.end(), {scene.positions[v].x, scene.positions[v].y, scene.positions[v].z});
    p.normals.insert(p.normals.end(), {scene.normals[v].x, scene.normals[v].y, scene.normals[v].z});
    if (!mesh.corner_uvs.empty()) {
      const Vec2f uv = mesh.corner_uvs[t][static_cast<std::size_t>(k)];
      p.uvs.insert(p.uvs.end(), {uv.x, uv.y});
    }
    if (!mesh.colors.empty() || uncoloured) push_linear(p.colors, scene.colors[v]);
  }
}

}  // namespace

SplatScene splat_scene(PointSet points, const std::string& source) {
  if (points.size() == 0) throw InputError("render.points.empty", source, "", "the point set is empty");
  estimate_radii(points);
  SplatScene s;
  if (!points.has_normals()) {
    // The baker's own estimate (same neighbourhoods, same orientation, on the points in the bake's
    // Morton order), so lighting matches and does not depend on the file's order.
    const std::vector<std::uint32_t> order = morton_order(points.positions);
    const std::vector<Vec3f> sorted = permuted(points, order).positions;
    const Neighborhoods nb = compute_neighborhoods(sorted);
    LocalFrames frames = compute_local_frames(sorted, nb);
    orient_normals(sorted, nb, nullptr, frames);
    s.normals.resize(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) s.normals[order[i]] = frames.normal[i];
  } else {
    s.normals = std::move(points.normals);
  }
  s.bounds = points.bounds();
  s.positions = std::move(points.positions);
  s.radii = std::move(points.radii);
  s.colors = points.has_colors() ? std::move(points.colors) : std::vector<Rgb8>(s.positions.size(), kBaseColor);
  return s;
}

MeshScene mesh_scene(const TriangleMesh& mesh, const std::string& source) {
  MeshScene s;
  s.positions = mesh.positions;
  s.bounds = mesh.bounds();
  s.colors = mesh.colors.empty() ? std::vector<Rgb8>(mesh.positions.size(), kBaseColor) : mesh.colors;
  s.normals = mesh.normals;
  const bool need_normals = s.normals.size() != s.positions.size();
  if (need_normals) s.normals.assign(s.positions.size(), Vec3f{});
  for (const Triangle& t : mesh.triangles) {
    s.indices.insert(s.indices.end(), t.begin(), t.end());
    if (!need_normals) continue;
    const Vec3f n = cross(s.positions[t[1]] - s.positions[t[0]], s.positions[t[2]] - s.positions[t[0]]);  // |n| = 2 area
    for (std::uint32_t v : t) s.normals[v] = s.normals[v] + n;
  }
  if (need_normals)
    for (Vec3f& n : s.normals) n = normalized(n);
  if (s.indices.empty()) throw InputError("render.mesh.empty", source, "", "the mesh has no triangles");
  return s;
}

EngineScene engine_scene(const MeshScene& mesh) {
  EngineScene s;
  EnginePrimitive p;
  p.material = reference_material();
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    p.positions.insert(p.positions.end(), {mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z});
    p.normals.insert(p.normals.end(), {mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z});
    push_linear(p.colors, mesh.colors[v]);
  }
  p.indices = mesh.indices;
  s.primitives.push_back(std::move(p));
  s.bounds = mesh.bounds;
  return s;
}

bool has_material_look(const TriangleMesh& mesh) {
  return !mesh.triangle_materials.empty() && (mesh.has_surface_color() || mesh.has_material_channels());
}

EngineScene engine_scene(const TriangleMesh& mesh, const MeshScene& scene) {
  if (!has_material_look(mesh)) return engine_scene(scene);
  EngineScene s;
  for (const TextureImage& t : mesh.textures) s.images.push_back(Image{t.width, t.height, t.rgba});
  // 1. Triangles bucketed by material, each bucket in file order (deterministic draw lists).
  std::vector<EnginePrimitive> by_material(mesh.materials.size());
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) by_material[m].material = engine_material(mesh.materials[m]);
  const bool uncoloured = !mesh.has_surface_color();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) push_corners(by_material[mesh.triangle_materials[t]], mesh, scene, t, uncoloured);
  // 2. Materials no triangle uses draw nothing.
  for (EnginePrimitive& p : by_material)
    if (!p.indices.empty()) s.primitives.push_back(std::move(p));
  s.bounds = scene.bounds;
  return s;
}

EngineScene engine_scene(const SplatScene& splats) {
  EngineScene s;
  s.images.push_back(disc_image());
  EnginePrimitive p;
  p.material = reference_material();
  p.material.base_texture = 0;
  p.material.alpha = EngineMaterial::Alpha::kMask;
  p.material.alpha_cutoff = 0.5f;
  const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
  for (std::size_t i = 0; i < splats.positions.size(); ++i) {
    const Vec3f n = splats.normals[i];
    const Vec3f a = std::fabs(n.x) < 0.9f ? Vec3f{1, 0, 0} : Vec3f{0, 1, 0};
    const Vec3f u = normalized(cross(n, a)), v = cross(n, u);
    const auto base = static_cast<std::uint32_t>(p.positions.size() / 3);
    for (int k = 0; k < 4; ++k) {
      const Vec3f q = splats.positions[i] + u * (su[k] * splats.radii[i]) + v * (sv[k] * splats.radii[i]);
      p.positions.insert(p.positions.end(), {q.x, q.y, q.z});
      p.normals.insert(p.normals.end(), {n.x, n.y, n.z});
      p.tangents.insert(p.tangents.end(), {u.x, u.y, u.z, 1.0f});
      p.uvs.insert(p.uvs.end(), {su[k] * 0.5f + 0.5f, sv[k] * 0.5f + 0.5f});
      push_linear(p.colors, splats.colors[i]);
    }
    p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  s.primitives.push_back(std::move(p));
  s.bounds = splats.bounds;
  return s;
}

}  // namespace qf::render
