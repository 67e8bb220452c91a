// Building blocks the generated assets share (tree.cpp, foliage.cpp, lattice.cpp, pylon.cpp,
// machine.cpp): seeded draws, tubes, beams, cards, and shapes painted into card textures. Internal
// to baker/shapes: the generators' public headers are tree.h, foliage.h, lattice.h, pylon.h, machine.h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/random.h"
#include "core/types.h"

namespace qf::shape_parts {

constexpr double kPi = 3.14159265358979323846;

inline Vec3f vec(double x, double y, double z) { return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)}; }

// Any two unit vectors perpendicular to unit d and to each other.
void frame(Vec3f d, Vec3f& a, Vec3f& b);

// A unit direction uniform on the sphere (the draws in this order: its height, then its azimuth).
struct Direction {
  double x, y, z;
};
Direction random_direction(SplitMix64& random);

// A point uniform in a ball of `radius` about the origin (a direction, then the distance), its
// height scaled by `squash` and raised by `lift`: where a plant's leaves gather about a tip.
Vec3f random_in_ball(SplitMix64& random, double radius, double squash, double lift);

// A tapered tube from `from` along unit `dir`, `length` long, radius r0 -> r1, open at both ends,
// smooth radial normals, with the bark's texture coordinates (u around, twice; v along, one repeat
// per unit); its triangles get material 0.
void add_tube(TriangleMesh& mesh, Vec3f from, Vec3f dir, double length, double r0, double r1, int sides = 10, int rings = 6);

// A beam of square section `width` from a to b: a box of 8 corners and 12 triangles, wound
// counter-clockwise seen from outside, no normals or materials (the caller assigns those).
void add_beam(TriangleMesh& mesh, Vec3f a, Vec3f b, float width);

// A card (leaf quad) at `at` facing unit `n`, its stalk end pointing along `along` (in its plane):
// `width` across, `length` along `n x along`'s perpendicular from the stalk; texture v = 1 at the
// stalk, 0 at the tip; wound counter-clockwise seen from where `n` points; material 1.
void add_leaf(TriangleMesh& mesh, Vec3f at, Vec3f n, Vec3f along, float length, float width);

// Bark (64 x 64, repeating; draws 4096 numbers) as material 0 and texture 0, and `leaf` (cut out by
// alpha at 0.5, double-sided, clamped) as material 1 and texture 1.
void add_plant_materials(TriangleMesh& mesh, SplitMix64& random);
// A card material: texture `texture` clamped, cut out by alpha (MASK), seen from both sides.
SurfaceMaterial card_material(const std::string& name, int texture);
TextureImage bark_texture(SplitMix64& random);

// A shape painted into a card texture: centred at (cx, cy) texels, its axis at `angle` radians
// (v = 0 at the end towards -axis, 1 at +axis, `length` texels apart), u across normalised by
// `half_span` texels. It covers the texels whose |u| <= profile(v) (profile in 0..1), opaque, in
// rgb x tone x (0.75 + 0.25 (1 - |u| / profile(v))): lighter along its midline, as a leaf's rib or a
// needle's ridge catches light. Texels it does not cover are left as they are.
struct PaintedShape {
  double cx = 0, cy = 0, angle = 0, length = 1, half_span = 1;
  std::array<double, 3> rgb{0, 0, 0};  // 0..255
  double tone = 1;
};
template <class Profile>
void paint_shape(TextureImage& t, const PaintedShape& s, Profile profile);

// The leaf's pointed oval over v in 0..1 (widest past the middle): the oak's leaves.
inline double leaf_profile(double v) { return 0.95 * std::sin(kPi * v) * std::sqrt(v); }

// ---- implementation of the template ----
template <class Profile>
void paint_shape(TextureImage& t, const PaintedShape& s, Profile profile) {
  // Only the texels of the shape's bounding square can be covered (profile <= 1).
  const double reach = 0.5 * s.length + s.half_span + 1;
  const int x0 = std::max(0, static_cast<int>(std::floor(s.cx - reach))), x1 = std::min(t.width - 1, static_cast<int>(std::ceil(s.cx + reach)));
  const int y0 = std::max(0, static_cast<int>(std::floor(s.cy - reach))), y1 = std::min(t.height - 1, static_cast<int>(std::ceil(s.cy + reach)));
  const double ca = std::cos(s.angle), sa = std::sin(s.angle);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double dx = x + 0.5 - s.cx, dy = y + 0.5 - s.cy;
      const double v = (dx * ca + dy * sa) / s.length + 0.5, u = (-dx * sa + dy * ca) / s.half_span;
      if (v < 0 || v > 1) continue;
      const double half_width = profile(v);
      if (std::fabs(u) > half_width) continue;
      const double shade = s.tone * (0.75 + 0.25 * (1 - std::fabs(u) / std::max(half_width, 1e-6)));
      std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * t.width + x) * 4];
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(std::min(255.0, s.rgb[static_cast<std::size_t>(c)] * shade));
      p[3] = 255;
    }
}

}  // namespace qf::shape_parts
