// A domain's triangles drawn onto its quad (surface_paint.h): a depth buffer at subsample
// resolution, then each texel's subsamples resolved into coverage, colour and normal.
#include "primitives/surface_paint.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/color.h"
#include "sample/surface_color.h"

namespace qf {
namespace {

// At most this many subsamples per quad (a 1024^2-texel quad gets 2 x 2 per texel, not 4 x 4):
// the depth buffer's 8 bytes each stay under 32 MB per thread.
constexpr std::size_t kMaxSubsamples = std::size_t{4} << 20;

// A triangle in subsample coordinates (subsample (x, y) centred at (x, y)) with its height over
// the plane, along the normal.
struct Projected {
  double x[3], y[3], h[3], area;
};

struct Subsamples {
  int width = 0, height = 0, per_side = 1;
  double step = 0;  // model units
  std::vector<float> height_of;        // nearest fragment's height (larger = nearer the viewer)
  std::vector<std::uint32_t> triangle;  // its index into the list, or kNone
};
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

Projected project(const TriangleMesh& mesh, std::uint32_t t, const PaintGrid& g, const Subsamples& s) {
  Projected p;
  for (int c = 0; c < 3; ++c) {
    const Vec3f x = mesh.positions[mesh.triangles[t][static_cast<std::size_t>(c)]] - g.center;
    p.x[c] = (dot(x, g.axis_u) + g.half_u) / s.step - 0.5;
    p.y[c] = (dot(x, g.axis_v) + g.half_v) / s.step - 0.5;
    p.h[c] = dot(x, g.normal);
  }
  p.area = (p.x[1] - p.x[0]) * (p.y[2] - p.y[0]) - (p.y[1] - p.y[0]) * (p.x[2] - p.x[0]);
  return p;
}

// Barycentric weights of (i, j) in p; false outside it.
bool weights(const Projected& p, double i, double j, double w[3]) {
  w[1] = ((i - p.x[0]) * (p.y[2] - p.y[0]) - (p.x[2] - p.x[0]) * (j - p.y[0])) / p.area;
  w[2] = ((p.x[1] - p.x[0]) * (j - p.y[0]) - (i - p.x[0]) * (p.y[1] - p.y[0])) / p.area;
  w[0] = 1 - w[1] - w[2];
  return w[0] >= 0 && w[1] >= 0 && w[2] >= 0;
}

// v as an int within [lo, hi] (v may be far outside int's range: a triangle reaching far past the grid).
int clamped(double v, int lo, int hi) { return static_cast<int>(std::clamp(v, double(lo), double(hi))); }

bool masked(const TriangleMesh& mesh, std::uint32_t t) {
  return !mesh.triangle_materials.empty() && mesh.materials[mesh.triangle_materials[t]].alpha_mode == AlphaMode::kMask;
}

// 1. The depth buffer: every triangle's subsamples, the nearest kept (a MASK cut-out is no
//    surface: what lies behind it shows).
void draw(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangles, const PaintGrid& g, Subsamples& s) {
  for (std::uint32_t k = 0; k < triangles.size(); ++k) {
    const std::uint32_t t = triangles[k];
    const Projected p = project(mesh, t, g, s);
    if (!(std::fabs(p.area) > 0)) continue;  // seen edge-on
    const bool mask = masked(mesh, t);
    const int i0 = clamped(std::ceil(std::min({p.x[0], p.x[1], p.x[2]})), 0, s.width);
    const int i1 = clamped(std::floor(std::max({p.x[0], p.x[1], p.x[2]})), -1, s.width - 1);
    const int j0 = clamped(std::ceil(std::min({p.y[0], p.y[1], p.y[2]})), 0, s.height);
    const int j1 = clamped(std::floor(std::max({p.y[0], p.y[1], p.y[2]})), -1, s.height - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        double w[3];
        if (!weights(p, i, j, w)) continue;
        const double h = w[0] * p.h[0] + w[1] * p.h[1] + w[2] * p.h[2];
        if (std::fabs(h) > g.slab) continue;
        const std::size_t q = static_cast<std::size_t>(j) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(i);
        if (s.triangle[q] != kNone && !(h > s.height_of[q])) continue;
        if (mask && !surface_color(mesh, t, w).surface) continue;
        s.height_of[q] = static_cast<float>(h);
        s.triangle[q] = k;
      }
  }
}

// The colour (linear RGB) and the unit normal of triangle t at weights w.
void look(const TriangleMesh& mesh, const std::vector<Vec3f>& normals, std::uint32_t t, const double w[3], const PaintGrid& g,
          float rgb[3], Vec3f& normal) {
  const Triangle& tri = mesh.triangles[t];
  if (!mesh.triangle_materials.empty() && mesh.has_surface_color()) {
    const Rgb8 c = surface_color(mesh, t, w).color;
    rgb[0] = srgb8_to_linear(c.r), rgb[1] = srgb8_to_linear(c.g), rgb[2] = srgb8_to_linear(c.b);
  } else if (mesh.colors.size() == mesh.positions.size()) {
    const Rgb8 c = interpolated_vertex_color(mesh, t, w);  // as the sampled points take it (sample.h)
    rgb[0] = srgb8_to_linear(c.r), rgb[1] = srgb8_to_linear(c.g), rgb[2] = srgb8_to_linear(c.b);
  } else {
    rgb[0] = srgb8_to_linear(g.base_color.r), rgb[1] = srgb8_to_linear(g.base_color.g), rgb[2] = srgb8_to_linear(g.base_color.b);
  }
  const Vec3f a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
  normal = normalized(cross(b - a, c - a), g.normal);
  if (normals.size() == mesh.positions.size()) {
    Vec3f sm{};
    for (int k = 0; k < 3; ++k) sm = sm + normals[tri[static_cast<std::size_t>(k)]] * static_cast<float>(w[k]);
    normal = normalized(sm, normal);
  }
  if (dot(normal, g.normal) < 0) normal = normal * -1.0f;
}

}  // namespace

std::vector<PaintedTexel> paint_surface(const TriangleMesh& mesh, const std::vector<Vec3f>& normals,
                                        const std::vector<std::uint32_t>& triangles, const PaintGrid& g) {
  const std::size_t texels = static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height);
  std::vector<PaintedTexel> out(texels);
  if (texels == 0 || triangles.empty()) return out;
  // The subsample grid.
  Subsamples s;
  s.per_side = std::max(1, g.samples);
  while (s.per_side > 1 && texels * static_cast<std::size_t>(s.per_side * s.per_side) > kMaxSubsamples) --s.per_side;
  s.width = g.width * s.per_side, s.height = g.height * s.per_side;
  s.step = g.texel / s.per_side;
  s.height_of.assign(static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height), 0.0f);
  s.triangle.assign(s.height_of.size(), kNone);
  draw(mesh, triangles, g, s);
  const bool channels = mesh.has_material_channels();
  // 2. Each texel from its subsamples.
  const double share = 1.0 / (s.per_side * s.per_side);
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      PaintedTexel& texel = out[static_cast<std::size_t>(j) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(i)];
      double rgb[3] = {0, 0, 0}, orm[3] = {0, 0, 0}, emissive[3] = {0, 0, 0};
      Vec3f nsum{};
      int covered = 0;
      for (int b = 0; b < s.per_side; ++b)
        for (int a = 0; a < s.per_side; ++a) {
          const int x = i * s.per_side + a, y = j * s.per_side + b;
          const std::uint32_t k = s.triangle[static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(x)];
          if (k == kNone) continue;
          const Projected p = project(mesh, triangles[k], g, s);
          double w[3];
          weights(p, x, y, w);
          for (double& v : w) v = std::clamp(v, 0.0, 1.0);
          float c[3];
          Vec3f n;
          look(mesh, normals, triangles[k], w, g, c, n);
          for (int ch = 0; ch < 3; ++ch) rgb[ch] += c[ch];
          if (channels) {
            const SurfaceChannels m = surface_channels(mesh, triangles[k], w);
            orm[0] += m.occlusion, orm[1] += m.roughness, orm[2] += m.metallic;
            for (int ch = 0; ch < 3; ++ch) emissive[ch] += m.emissive[static_cast<std::size_t>(ch)];
          }
          nsum = nsum + n;
          ++covered;
        }
      if (covered == 0) continue;
      texel.coverage = static_cast<float>(covered * share);
      for (int ch = 0; ch < 3; ++ch) texel.color[static_cast<std::size_t>(ch)] = static_cast<float>(rgb[ch] / covered);
      if (channels)
        for (std::size_t ch = 0; ch < 3; ++ch) {
          texel.orm[ch] = static_cast<float>(orm[ch] / covered);
          texel.emissive[ch] = static_cast<float>(emissive[ch] / covered);
        }
      const Vec3f n = normalized(nsum, g.normal);
      texel.normal = {dot(n, g.axis_u), dot(n, g.axis_v), dot(n, g.normal)};
    }
  return out;
}

}  // namespace qf
