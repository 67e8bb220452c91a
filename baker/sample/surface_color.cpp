// Material colour at a surface point (surface_color.h).
#include "sample/surface_color.h"

#include <cmath>

#include "core/color.h"

namespace qf {
namespace {

// A texel index brought into 0..n-1 by the wrap mode.
int wrap_index(int i, int n, TextureWrap mode) {
  if (mode == TextureWrap::kClampToEdge) return i < 0 ? 0 : i >= n ? n - 1 : i;
  if (mode == TextureWrap::kMirroredRepeat) {
    const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
    return m < n ? m : 2 * n - 1 - m;
  }
  return ((i % n) + n) % n;
}

}  // namespace

std::array<float, 4> sample_texture(const TextureImage& image, Vec2f uv, TextureWrap wrap_s, TextureWrap wrap_t) {
  // Texel centres lie at (i + 0.5) / width; repeating wraps work on any coordinate, so the
  // fraction is taken before the (float) product can lose precision far from 0..1.
  const double fu = wrap_s == TextureWrap::kRepeat ? uv.x - std::floor(uv.x) : uv.x;
  const double fv = wrap_t == TextureWrap::kRepeat ? uv.y - std::floor(uv.y) : uv.y;
  const double x = std::isfinite(fu) ? fu * image.width - 0.5 : 0, y = std::isfinite(fv) ? fv * image.height - 0.5 : 0;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double ax = x - x0, ay = y - y0;
  std::array<float, 4> out{0, 0, 0, 0};
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const double weight = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay);
      if (weight == 0) continue;
      const int ix = wrap_index(static_cast<int>(std::fmax(std::fmin(x0, 1e9), -1e9)) + dx, image.width, wrap_s);
      const int iy = wrap_index(static_cast<int>(std::fmax(std::fmin(y0, 1e9), -1e9)) + dy, image.height, wrap_t);
      const std::uint8_t* t = &image.rgba[(static_cast<std::size_t>(iy) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(ix)) * 4];
      for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(c)] += static_cast<float>(weight * srgb8_to_linear(t[c]));
      out[3] += static_cast<float>(weight * t[3] / 255.0);
    }
  return out;
}

SurfaceColor surface_color(const TriangleMesh& mesh, std::size_t t, const double w[3]) {
  const Triangle& tri = mesh.triangles[t];
  // 1. The material's factor and texture.
  double rgba[4] = {1, 1, 1, 1};
  const SurfaceMaterial* m = mesh.triangle_materials.empty() ? nullptr : &mesh.materials[mesh.triangle_materials[t]];
  if (m) {
    for (int c = 0; c < 4; ++c) rgba[c] = m->base_color[static_cast<std::size_t>(c)];
    if (m->texture >= 0 && !mesh.corner_uvs.empty()) {
      const std::array<Vec2f, 3>& uv = mesh.corner_uvs[t];
      const Vec2f at{static_cast<float>(w[0] * uv[0].x + w[1] * uv[1].x + w[2] * uv[2].x),
                     static_cast<float>(w[0] * uv[0].y + w[1] * uv[1].y + w[2] * uv[2].y)};
      const std::array<float, 4> texel = sample_texture(mesh.textures[static_cast<std::size_t>(m->texture)], at, m->wrap_s, m->wrap_t);
      for (int c = 0; c < 4; ++c) rgba[c] *= texel[static_cast<std::size_t>(c)];
    }
  }
  // 2. The vertex colours, interpolated in linear light.
  if (!mesh.colors.empty()) {
    for (int c = 0; c < 3; ++c) {
      double v = 0;
      for (int k = 0; k < 3; ++k) {
        const Rgb8 col = mesh.colors[tri[static_cast<std::size_t>(k)]];
        v += w[k] * srgb8_to_linear(c == 0 ? col.r : c == 1 ? col.g : col.b);
      }
      rgba[c] *= v;
    }
  }
  SurfaceColor out;
  out.color = {linear_to_srgb8(rgba[0]), linear_to_srgb8(rgba[1]), linear_to_srgb8(rgba[2])};
  out.surface = !(m && m->alpha_mode == AlphaMode::kMask && rgba[3] < m->alpha_cutoff);
  return out;
}

}  // namespace qf
