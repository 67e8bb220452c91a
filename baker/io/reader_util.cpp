// Shared reader helpers: token quoting and non-finite point removal.
#include "io/reader_util.h"

#include <algorithm>

namespace qf::io {

std::string quote_token(std::string_view t) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < t.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (t.size() > kMax) out += "...";
  return out + "'";
}

template <class T>
static void erase_indices(std::vector<T>& v, const std::vector<char>& drop) {
  if (v.empty()) return;
  std::size_t w = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!drop[i]) v[w++] = v[i];
  v.resize(w);
}

void NonFiniteFilter::apply(PointSet& points, ReadReport* report, std::size_t first) {
  if (dropped_.empty()) return;
  std::vector<char> drop(points.size(), 0);
  for (std::size_t i : dropped_) drop[i - first] = 1;
  erase_points(points, drop);
  if (report) report->dropped_nonfinite += dropped_.size();
  dropped_.clear();
}

void NonFiniteFilter::apply(TriangleMesh& mesh, ReadReport* report) const {
  if (dropped_.empty()) return;
  const std::size_t n = mesh.positions.size();
  std::vector<char> drop(n, 0);
  for (std::size_t i : dropped_) drop[i] = 1;
  std::vector<std::uint32_t> remap(n, 0);
  std::uint32_t next = 0;
  for (std::size_t i = 0; i < n; ++i) remap[i] = drop[i] ? 0 : next++;
  std::size_t w = 0, removed = 0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle t = mesh.triangles[i];
    if (drop[t[0]] || drop[t[1]] || drop[t[2]]) {
      ++removed;
      continue;
    }
    // Per-triangle materials and texture coordinates move with their triangles.
    if (!mesh.triangle_materials.empty()) mesh.triangle_materials[w] = mesh.triangle_materials[i];
    if (!mesh.corner_uvs.empty()) mesh.corner_uvs[w] = mesh.corner_uvs[i];
    mesh.triangles[w++] = {remap[t[0]], remap[t[1]], remap[t[2]]};
  }
  mesh.triangles.resize(w);
  if (!mesh.triangle_materials.empty()) mesh.triangle_materials.resize(w);
  if (!mesh.corner_uvs.empty()) mesh.corner_uvs.resize(w);
  erase_indices(mesh.positions, drop);
  erase_indices(mesh.normals, drop);
  erase_indices(mesh.colors, drop);
  if (report) {
    report->dropped_nonfinite += dropped_.size();
    report->dropped_triangles += removed;
  }
}

}  // namespace qf::io
