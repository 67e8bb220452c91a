// Material colour at a surface point (surface_color.h).
#include "sample/surface_color.h"

#include <cmath>

#include "core/color.h"

namespace qf {
namespace {

// A texel index brought into 0..n-1 by the wrap mode. Bilinear lookups inside the image, or one
// texel past an edge (most of those at an edge), are answered before the divisions.
int wrap_index(int i, int n, TextureWrap mode) {
  if (i >= 0 && i < n) return i;  // every mode leaves these alone
  if (i == -1) return mode == TextureWrap::kRepeat ? n - 1 : 0;
  if (i == n) return mode == TextureWrap::kRepeat ? 0 : n - 1;
  if (mode == TextureWrap::kClampToEdge) return i < 0 ? 0 : n - 1;
  if (mode == TextureWrap::kMirroredRepeat) {
    const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
    return m < n ? m : 2 * n - 1 - m;
  }
  return ((i % n) + n) % n;
}

// std::floor, without the libm call it is on baseline x86-64 (no SSE4.1 rounding instruction):
// the same value for |v| < 2^52 (beyond, every double is an integer and std::floor answers), but
// for the sign of a zero result, which no lookup below depends on (a zero fraction or offset
// gives the same texel and weights).
double floor_of(double v) {
  if (!(std::fabs(v) < 4503599627370496.0)) return std::floor(v);
  const double t = static_cast<double>(static_cast<long long>(v));
  return t > v ? t - 1 : t;
}

// A texel column or row as an int: the floored coordinate bounded to +-1e9 (far outside any
// image, and inside int).
int texel_index(double floored) {
  if (floored >= -1e9 && floored <= 1e9) return static_cast<int>(floored);
  return static_cast<int>(std::fmax(std::fmin(floored, 1e9), -1e9));
}

// sample_texture, with the alpha sum only when `kAlpha` (only MASK materials look at it); texels
// read as sRGB colours, or as linear data (metallic, roughness, occlusion) when !kSrgb.
template <bool kAlpha, bool kSrgb = true>
std::array<float, 4> bilinear(const TextureImage& image, Vec2f uv, TextureWrap wrap_s, TextureWrap wrap_t) {
  // Texel centres lie at (i + 0.5) / width; repeating wraps work on any coordinate, so the
  // fraction is taken before the (float) product can lose precision far from 0..1.
  // (The fraction in float arithmetic: a float's floor is a float, exactly.)
  const double fu = wrap_s == TextureWrap::kRepeat ? uv.x - static_cast<float>(floor_of(uv.x)) : uv.x;
  const double fv = wrap_t == TextureWrap::kRepeat ? uv.y - static_cast<float>(floor_of(uv.y)) : uv.y;
  const double x = std::isfinite(fu) ? fu * image.width - 0.5 : 0, y = std::isfinite(fv) ? fv * image.height - 0.5 : 0;
  const double x0 = floor_of(x), y0 = floor_of(y);
  const double ax = x - x0, ay = y - y0;
  // The two columns and rows, wrapped once (not per texel).
  const int cx = texel_index(x0), cy = texel_index(y0);
  const int ix[2] = {wrap_index(cx, image.width, wrap_s), wrap_index(cx + 1, image.width, wrap_s)};
  const int iy[2] = {wrap_index(cy, image.height, wrap_t), wrap_index(cy + 1, image.height, wrap_t)};
  // Sums in plain locals, not the array (which compilers keep in memory, a store and a load per
  // add): the same float additions in the same order.
  float r = 0, g = 0, b = 0, a = 0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const double weight = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay);
      if (weight == 0) continue;
      const std::uint8_t* t = &image.rgba[(static_cast<std::size_t>(iy[dy]) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(ix[dx])) * 4];
      r += static_cast<float>(weight * (kSrgb ? srgb8_to_linear(t[0]) : t[0] / 255.0));
      g += static_cast<float>(weight * (kSrgb ? srgb8_to_linear(t[1]) : t[1] / 255.0));
      b += static_cast<float>(weight * (kSrgb ? srgb8_to_linear(t[2]) : t[2] / 255.0));
      if (kAlpha) a += static_cast<float>(weight * t[3] / 255.0);
    }
  return {r, g, b, a};
}

}  // namespace

std::array<float, 4> sample_texture(const TextureImage& image, Vec2f uv, TextureWrap wrap_s, TextureWrap wrap_t) {
  return bilinear<true>(image, uv, wrap_s, wrap_t);
}

Rgb8 interpolated_vertex_color(const TriangleMesh& mesh, std::size_t t, const double w[3]) {
  const Triangle& tri = mesh.triangles[t];
  double c[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    const Rgb8 col = mesh.colors[tri[static_cast<std::size_t>(k)]];
    c[0] += w[k] * col.r, c[1] += w[k] * col.g, c[2] += w[k] * col.b;
  }
  return {static_cast<std::uint8_t>(std::lround(c[0])), static_cast<std::uint8_t>(std::lround(c[1])),
          static_cast<std::uint8_t>(std::lround(c[2]))};
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
      // Alpha decides nothing but MASK cut-outs (BLEND is kept as opaque surface, docs/formats.md).
      const TextureImage& image = mesh.textures[static_cast<std::size_t>(m->texture)];
      const bool mask = m->alpha_mode == AlphaMode::kMask;
      const std::array<float, 4> texel =
          mask ? bilinear<true>(image, at, m->wrap_s, m->wrap_t) : bilinear<false>(image, at, m->wrap_s, m->wrap_t);
      for (int c = 0; c < (mask ? 4 : 3); ++c) rgba[c] *= texel[static_cast<std::size_t>(c)];
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

SurfaceChannels surface_channels(const TriangleMesh& mesh, std::size_t t, const double w[3]) {
  SurfaceChannels out;
  if (mesh.triangle_materials.empty()) return out;
  const SurfaceMaterial& m = mesh.materials[mesh.triangle_materials[t]];
  out.roughness = m.roughness, out.metallic = m.metallic, out.emissive = m.emissive;
  if (mesh.corner_uvs.empty()) return out;
  const std::array<Vec2f, 3>& uv = mesh.corner_uvs[t];
  const Vec2f at{static_cast<float>(w[0] * uv[0].x + w[1] * uv[1].x + w[2] * uv[2].x),
                 static_cast<float>(w[0] * uv[0].y + w[1] * uv[1].y + w[2] * uv[2].y)};
  auto texel = [&](const TextureRef& r, bool srgb) {
    const TextureImage& image = mesh.textures[static_cast<std::size_t>(r.image)];
    return srgb ? bilinear<false, true>(image, at, r.wrap_s, r.wrap_t) : bilinear<false, false>(image, at, r.wrap_s, r.wrap_t);
  };
  if (m.metallic_roughness.image >= 0) {
    const std::array<float, 4> mr = texel(m.metallic_roughness, false);
    out.roughness *= mr[1], out.metallic *= mr[2];
  }
  if (m.occlusion.image >= 0) out.occlusion = 1 + m.occlusion_strength * (texel(m.occlusion, false)[0] - 1);
  if (m.emissive_texture.image >= 0) {
    const std::array<float, 4> e = texel(m.emissive_texture, true);
    for (std::size_t c = 0; c < 3; ++c) out.emissive[c] *= e[c];
  }
  return out;
}

}  // namespace qf
