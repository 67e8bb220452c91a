// Small helpers of the plain value types (bounds, memory accounting, Morton order, permutations).
#include "core/types.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <tuple>

namespace qf {

Vec3f normalized(Vec3f a, Vec3f fallback) {
  const float len = length(a);
  if (!(len > 0.0f) || !std::isfinite(len)) return fallback;
  return a * (1.0f / len);
}

double canonical_double(float v) {
  if (v == 0.0f) return 0.0;
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf - 1, v);
  *r.ptr = '\0';
  return std::strtod(buf, nullptr);
}

double round_to(double v, int digits) {
  const double scale = std::pow(10.0, digits);
  return std::round(v * scale) / scale;
}

Vec3f as_unit(Vec3f a, Vec3f fallback) {
  const float len2 = dot(a, a);
  if (std::fabs(len2 - 1.0f) <= 4e-7f) return a;
  return normalized(a, fallback);
}

void Bounds::add(Vec3f p) {
  min = {std::min(min.x, p.x), std::min(min.y, p.y), std::min(min.z, p.z)};
  max = {std::max(max.x, p.x), std::max(max.y, p.y), std::max(max.z, p.z)};
}

static Bounds bounds_of(const std::vector<Vec3f>& points) {
  Bounds b;
  for (const Vec3f& p : points) b.add(p);
  return b;
}

Bounds PointSet::bounds() const { return bounds_of(positions); }

std::uint64_t morton_code(Vec3f p, const Bounds& box) {
  const Vec3f size = box.size();
  const float extent = std::max({size.x, size.y, size.z, 1e-30f});
  auto spread = [](std::uint64_t v) {  // 21 bits -> every third bit of 63
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
  };
  std::uint64_t c[3];
  for (int a = 0; a < 3; ++a) c[a] = static_cast<std::uint64_t>(std::clamp((p[a] - box.min[a]) / extent, 0.0f, 1.0f) * 2097151.0f);
  return spread(c[0]) | spread(c[1]) << 1 | spread(c[2]) << 2;
}

std::vector<std::uint32_t> morton_order(const std::vector<Vec3f>& positions) {
  const Bounds box = bounds_of(positions);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) keys[i] = {morton_code(positions[i], box), static_cast<std::uint32_t>(i)};
  // Ties (points in one cell) by position, so that only points at the very same position keep
  // their input order; then by index (MortonKey's order).
  std::sort(keys.begin(), keys.end(), [&](const auto& a, const auto& b) {
    return MortonKey{a.first, positions[a.second], a.second} < MortonKey{b.first, positions[b.second], b.second};
  });
  std::vector<std::uint32_t> order(positions.size());
  for (std::size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].second;
  return order;
}

PointSet permuted(const PointSet& points, const std::vector<std::uint32_t>& order) {
  PointSet out;
  auto take = [&order](const auto& in, auto& dst) {
    if (in.empty()) return;
    dst.reserve(order.size());
    for (std::uint32_t i : order) dst.push_back(in[i]);
  };
  take(points.positions, out.positions);
  take(points.normals, out.normals);
  take(points.radii, out.radii);
  take(points.colors, out.colors);
  out.scalars.resize(points.scalars.size());
  for (std::size_t f = 0; f < points.scalars.size(); ++f) {
    out.scalars[f].name = points.scalars[f].name;
    take(points.scalars[f].values, out.scalars[f].values);
  }
  out.comments = points.comments;
  return out;
}
namespace {

template <class T>
void erase_marked(std::vector<T>& v, const std::vector<char>& drop) {
  if (v.empty()) return;
  std::size_t w = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!drop[i]) v[w++] = v[i];
  v.resize(w);
  v.shrink_to_fit();
}

}  // namespace

void erase_points(PointSet& points, const std::vector<char>& drop) {
  if (drop.size() != points.size()) throw std::logic_error("erase_points: one flag per point");
  erase_marked(points.positions, drop);
  erase_marked(points.normals, drop);
  erase_marked(points.radii, drop);
  erase_marked(points.colors, drop);
  for (ScalarField& s : points.scalars) erase_marked(s.values, drop);
}

Bounds TriangleMesh::bounds() const { return bounds_of(positions); }

std::vector<Vec3f> TriangleMesh::smooth_normals() const {
  // Area-weighted face normals summed per position, so vertices split at a seam share one normal.
  std::map<std::tuple<float, float, float>, Vec3f> at;
  const auto key = [](Vec3f p) { return std::make_tuple(p.x, p.y, p.z); };
  for (const Triangle& t : triangles) {
    const Vec3f n = cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
    for (std::uint32_t v : t) {
      Vec3f& s = at[key(positions[v])];
      s = s + n;
    }
  }
  std::vector<Vec3f> smooth(positions.size(), Vec3f{0, 0, 1});
  for (std::size_t v = 0; v < smooth.size(); ++v) {
    const auto it = at.find(key(positions[v]));
    if (it != at.end() && dot(it->second, it->second) > 0) smooth[v] = normalized(it->second);
  }
  return smooth;
}

template <class T>
static std::size_t bytes(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

std::size_t PointSet::memory_bytes() const {
  std::size_t total = bytes(positions) + bytes(normals) + bytes(radii) + bytes(colors);
  for (const ScalarField& s : scalars) total += bytes(s.values);
  return total;
}

std::size_t TriangleMesh::memory_bytes() const {
  std::size_t total = bytes(positions) + bytes(triangles) + bytes(normals) + bytes(colors) +
                      bytes(triangle_materials) + bytes(corner_uvs);
  for (const TextureImage& t : textures) total += bytes(t.rgba);
  return total;
}

bool TriangleMesh::has_surface_color() const {
  if (!colors.empty()) return true;
  for (const SurfaceMaterial& m : materials)
    if (m.texture >= 0 || m.base_color[0] != 1 || m.base_color[1] != 1 || m.base_color[2] != 1) return true;
  return false;
}

bool TriangleMesh::has_material_channels() const {
  for (const SurfaceMaterial& m : materials)
    if (m.metallic != 0 || m.roughness != 1 || m.emissive != std::array<float, 3>{0, 0, 0} || m.metallic_roughness.image >= 0 ||
        m.emissive_texture.image >= 0 || m.occlusion.image >= 0)
      return true;
  return false;
}

}  // namespace qf
