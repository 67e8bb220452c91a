// The crossed billboard (billboard.h).
#include "primitives/billboard.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/color.h"
#include "primitives/surface_paint.h"

namespace qf {
namespace {

// One card: the asset seen along `normal` drawn onto the rectangle through `center` spanned by
// axis_u, axis_v (covering the asset's extent along them), added to `out` as a quad with its own
// material and texture.
void add_card(TriangleMesh& out, const TriangleMesh& mesh, const std::vector<std::uint32_t>& all, Vec3f center, Vec3f axis_u,
              Vec3f axis_v, const BillboardOptions& o) {
  // 1. The asset's extent along the card's axes.
  double half_u = 0, half_v = 0, depth = 0;
  const Vec3f normal = cross(axis_u, axis_v);
  for (const Vec3f& p : mesh.positions) {
    const Vec3f d = p - center;
    half_u = std::max(half_u, std::fabs(double(dot(d, axis_u))));
    half_v = std::max(half_v, std::fabs(double(dot(d, axis_v))));
    depth = std::max(depth, std::fabs(double(dot(d, normal))));
  }
  const double texel = 2 * std::max({half_u, half_v, 1e-30}) / std::max(1, o.side);
  PaintGrid g{center, axis_u, axis_v, normal, std::max(1, static_cast<int>(std::ceil(2 * half_u / texel))),
              std::max(1, static_cast<int>(std::ceil(2 * half_v / texel))), texel, 0, 0, 2 * depth + 1, 4, kUncolouredColor};
  g.half_u = 0.5 * g.width * texel, g.half_v = 0.5 * g.height * texel;
  // 2. The view, as an RGBA image (row 0 at the top: t = +half_v), colour bled into cut-away texels.
  const std::vector<PaintedTexel> view = paint_surface(mesh, {}, all, g);
  TextureImage image{g.width, g.height, std::vector<std::uint8_t>(4 * view.size(), 0)};
  std::vector<float> colour(3 * view.size(), 0.0f);
  std::vector<char> known(view.size(), 0);
  for (std::size_t k = 0; k < view.size(); ++k)
    if (view[k].coverage > 0) {
      known[k] = 1;
      for (int c = 0; c < 3; ++c) colour[3 * k + static_cast<std::size_t>(c)] = view[k].color[static_cast<std::size_t>(c)];
    }
  // Bleeding: a few passes of the mean of known 4-neighbours, so mipmaps and filtering pull no black in.
  for (int pass = 0; pass < 8; ++pass) {
    std::vector<char> next = known;
    for (int j = 0; j < g.height; ++j)
      for (int i = 0; i < g.width; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(i);
        if (known[k]) continue;
        float sum[3] = {0, 0, 0};
        int n = 0;
        const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
        for (int e = 0; e < 4; ++e) {
          const int a = i + di[e], b = j + dj[e];
          if (a < 0 || b < 0 || a >= g.width || b >= g.height) continue;
          const std::size_t q = static_cast<std::size_t>(b) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(a);
          if (!known[q]) continue;
          for (int c = 0; c < 3; ++c) sum[c] += colour[3 * q + static_cast<std::size_t>(c)];
          ++n;
        }
        if (n == 0) continue;
        for (int c = 0; c < 3; ++c) colour[3 * k + static_cast<std::size_t>(c)] = sum[c] / static_cast<float>(n);
        next[k] = 1;
      }
    known = std::move(next);
  }
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(i);
      std::uint8_t* p = &image.rgba[4 * (static_cast<std::size_t>(g.height - 1 - j) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(i))];
      for (int c = 0; c < 3; ++c) p[c] = linear_to_srgb8(colour[3 * k + static_cast<std::size_t>(c)]);
      p[3] = static_cast<std::uint8_t>(std::lround(255.0 * view[k].coverage));
    }
  // 3. The quad, its texture and material.
  const auto base = static_cast<std::uint32_t>(out.positions.size());
  const Vec3f du = axis_u * static_cast<float>(g.half_u), dv = axis_v * static_cast<float>(g.half_v);
  out.positions.insert(out.positions.end(), {center - du - dv, center + du - dv, center + du + dv, center - du + dv});
  out.triangles.push_back({base, base + 1, base + 2});
  out.corner_uvs.push_back({Vec2f{0, 1}, Vec2f{1, 1}, Vec2f{1, 0}});
  out.triangles.push_back({base, base + 2, base + 3});
  out.corner_uvs.push_back({Vec2f{0, 1}, Vec2f{1, 0}, Vec2f{0, 0}});
  SurfaceMaterial m;
  m.name = "card" + std::to_string(out.materials.size());
  m.texture = static_cast<int>(out.textures.size());
  m.wrap_s = m.wrap_t = TextureWrap::kClampToEdge;
  m.alpha_mode = AlphaMode::kMask;
  m.alpha_cutoff = o.alpha_cutoff;
  m.double_sided = true;
  out.triangle_materials.insert(out.triangle_materials.end(), 2, static_cast<std::uint32_t>(out.materials.size()));
  out.materials.push_back(m);
  out.textures.push_back(std::move(image));
}

}  // namespace

TriangleMesh crossed_billboard(const TriangleMesh& mesh, const BillboardOptions& o) {
  std::vector<std::uint32_t> all(mesh.triangles.size());
  std::iota(all.begin(), all.end(), 0u);
  const Vec3f center = mesh.bounds().center();
  TriangleMesh out;
  constexpr double kPi = 3.14159265358979323846;
  for (int k = 0; k < 3; ++k) {
    const double a = kPi * k / 3;  // 0, 60, 120 degrees about the vertical
    add_card(out, mesh, all, center, Vec3f{static_cast<float>(std::cos(a)), 0, static_cast<float>(-std::sin(a))}, Vec3f{0, 1, 0}, o);
  }
  add_card(out, mesh, all, center, Vec3f{1, 0, 0}, Vec3f{0, 0, -1}, o);  // seen from above (normal +y)
  return out;
}

}  // namespace qf
