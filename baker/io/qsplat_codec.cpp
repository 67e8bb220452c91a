// QSplat quantisation tables and encoders (shared/specs/qsplat-format.md §3–§6).
#include "io/qsplat_codec.h"

#include <algorithm>
#include <cmath>

namespace qf::qsplat {
namespace {

constexpr int kGrid = 13;  // sphere grid cells per axis (§3.2)
constexpr int kNormalCells = 52;

// Index of the first table entry of each size s (1..13), and a lookup (s, x, y, z) -> index or -1.
struct SphereIndex {
  std::array<SphereEntry, kSphereEntries> table{};
  // [s][x][y][z], s in 1..13, x,y,z in 0..12
  std::array<std::int16_t, 14 * 13 * 13 * 13> lookup{};
};

const SphereIndex& sphere_index() {
  static const SphereIndex index = [] {
    SphereIndex idx;
    idx.lookup.fill(-1);
    const float inv = 1.0f / float(kGrid);
    const float sqrt3 = std::sqrt(3.0f);
    int n = 0;
    for (int s = 1; s <= kGrid; ++s)
      for (int x = 0; x <= kGrid - s; ++x)
        for (int y = 0; y <= kGrid - s; ++y)
          for (int z = 0; z <= kGrid - s; ++z) {
            const float X = float(s + 2 * x) * inv - 1.0f;
            const float Y = float(s + 2 * y) * inv - 1.0f;
            const float Z = float(s + 2 * z) * inv - 1.0f;
            const float R = float(s) * inv;
            const float bound = 1.0f + sqrt3 * R;
            if (X * X + Y * Y + Z * Z > bound * bound) continue;
            idx.table[n] = {X, Y, Z, R};
            idx.lookup[((s * 13 + x) * 13 + y) * 13 + z] = static_cast<std::int16_t>(n);
            ++n;
          }
    return idx;
  }();
  return index;
}

float normal_coordinate(int i) {
  const float w = (float(i) + 0.5f) * (2.0f / float(kNormalCells)) - 1.0f;
  return std::clamp(std::tan(w * float(M_PI / 4)), -1.0f, 1.0f);
}

}  // namespace

const std::array<SphereEntry, kSphereEntries>& sphere_table() { return sphere_index().table; }

const std::array<Vec3f, 16384>& normal_table() {
  static const std::array<Vec3f, 16384> table = [] {
    std::array<Vec3f, 16384> t{};
    for (int i = 0; i < 16384; ++i) t[i] = {0, 0, 1};
    for (int a = 0; a < 6; ++a)
      for (int u = 0; u < kNormalCells; ++u)
        for (int v = 0; v < kNormalCells; ++v) {
          const float cu = normal_coordinate(u), cv = normal_coordinate(v);
          float m = std::sqrt(std::max(0.0f, 1.0f - cu * cu - cv * cv));
          if (a & 1) m = -m;
          Vec3f n;
          switch (a >> 1) {
            case 0: n = {m, cu, cv}; break;
            case 1: n = {cv, m, cu}; break;
            default: n = {cu, cv, m}; break;
          }
          t[a * 2704 + u * kNormalCells + v] = normalized(n);
        }
    return t;
  }();
  return table;
}

int encode_sphere(const float c[3], float r, const float pc[3], float pr) {
  const SphereIndex& idx = sphere_index();
  int lo[3], hi[3];
  float t[3];
  const float q = pr > 0 ? r / pr : 1.0f;
  int s = 1;
  for (int k = 0; k < 3; ++k) {
    t[k] = pr > 0 ? 0.5f * ((c[k] - pc[k]) / pr + 1.0f) : 0.5f;
    const float tk = t[k];
    lo[k] = std::clamp(static_cast<int>(std::floor((tk - 0.5f * q) * kGrid)), 0, kGrid - 1);
    hi[k] = std::clamp(static_cast<int>(std::ceil((tk + 0.5f * q) * kGrid)), 1, kGrid);
    s = std::max(s, hi[k] - lo[k]);
  }
  for (; s <= kGrid; ++s) {
    // Any x in [hi - s, lo] (within the grid) gives a cube [x, x+s] covering [lo, hi]; take the one
    // whose centre is nearest the child's, which keeps the decoded centre close to the point.
    int x[3];
    for (int k = 0; k < 3; ++k) {
      const int xmin = std::max(0, hi[k] - s), xmax = std::min(lo[k], kGrid - s);
      x[k] = std::clamp(static_cast<int>(std::lround(t[k] * kGrid - 0.5f * float(s))), xmin, xmax);
    }
    const int i = idx.lookup[((s * 13 + x[0]) * 13 + x[1]) * 13 + x[2]];
    if (i >= 0) return i;
  }
  return kSphereEntries - 1;  // not reached: size 13 at (0,0,0) is always in the table
}

int encode_normal(Vec3f n) {
  const float ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  int a;
  float u, v, dom;
  if (ax > ay && ax > az) {
    a = 0; dom = n.x; u = n.y; v = n.z;
  } else if (ax > ay) {
    a = 4; dom = n.z; u = n.x; v = n.y;
  } else if (ay > az) {
    a = 2; dom = n.y; u = n.z; v = n.x;
  } else {
    a = 4; dom = n.z; u = n.x; v = n.y;
  }
  if (dom < 0) a += 1;
  auto cell = [](float t) {
    const float w = std::clamp(std::atan(t) * float(4.0 / M_PI), -1.0f, 1.0f);
    return std::min(static_cast<int>(std::floor((w + 1.0f) * 26.0f)), kNormalCells - 1);
  };
  return a * 2704 + cell(u) * kNormalCells + cell(v);
}

int encode_cone(float half_angle) {
  const float s = half_angle <= 1.5f ? std::sin(std::max(0.0f, half_angle)) : 0.999f;
  return std::min(3, static_cast<int>(std::floor(4.0f * std::sqrt(s))));
}

}  // namespace qf::qsplat
