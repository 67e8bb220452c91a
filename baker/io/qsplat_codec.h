// QSplat 1.0 (file version 11) quantisation tables and codecs, shared by the reader and the
// writer. Byte-level facts come from shared/specs/qsplat-format.md (section numbers below).
#pragma once

#include <array>
#include <cstdint>

#include "core/types.h"

namespace qf::qsplat {

constexpr int kSphereEntries = 7621;   // valid sphere indices 0..7620 (§3.2)
constexpr int kNormalEntries = 16224;  // valid normal indices 0..16223 (§4.1)
constexpr int kHeaderBytes = 40;       // data fragment header (§1.2)
constexpr int kCommentHeaderBytes = 20;  // comment fragment header (§1.4)
constexpr std::uint32_t kOptionColor = 1, kOptionComment = 2;

struct SphereEntry {
  float x, y, z, r;  // centre offset and radius in units of the parent radius
};

// The 13-bit sphere table (§3.2), built with the original's f32 arithmetic.
const std::array<SphereEntry, kSphereEntries>& sphere_table();
// The 14-bit normal table (§4.1); cells with c_U² + c_V² > 1 are clamped (never NaN).
const std::array<Vec3f, 16384>& normal_table();

// Decodes a child sphere against its parent's decoded sphere, in f32 as the original (§3.1).
inline void decode_sphere(const SphereEntry& e, const float parent_center[3], float parent_radius, float center[3],
                          float& radius) {
  center[0] = parent_center[0] + parent_radius * e.x;
  center[1] = parent_center[1] + parent_radius * e.y;
  center[2] = parent_center[2] + parent_radius * e.z;
  radius = parent_radius * e.r;
}

// Chooses the table entry for child sphere (c, r) under decoded parent (pc, pr): §3.4's covering
// cube of s cells, but placed (among the positions that still cover the child's extent) so its
// centre is nearest the child's, instead of the original's one-cell widening ("XXX - FIXME"),
// which can fall short and return an invalid index. A cube cut from the table is replaced by the
// next larger size, so the result is always a valid index. The decoder does not care (§3.4).
int encode_sphere(const float c[3], float r, const float pc[3], float pr);

// Normal index for a unit vector (§4.3, without the random dither so output is deterministic).
int encode_normal(Vec3f n);
// Cone code KK for a half-angle in radians (§5).
int encode_cone(float half_angle);

// RGB565 (§6).
inline std::uint16_t encode_color(Rgb8 c) {
  return static_cast<std::uint16_t>(((c.r >> 3) << 11) | ((c.g >> 2) << 5) | (c.b >> 3));
}
inline Rgb8 decode_color(std::uint16_t v) {
  const unsigned r5 = v >> 11, g6 = (v >> 5) & 63, b5 = v & 31;
  return {static_cast<std::uint8_t>((r5 << 3) | (r5 >> 2)), static_cast<std::uint8_t>((g6 << 2) | (g6 >> 4)),
          static_cast<std::uint8_t>((b5 << 3) | (b5 >> 2))};
}

}  // namespace qf::qsplat
