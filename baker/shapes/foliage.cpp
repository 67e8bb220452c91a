// The conifer and the grass clump (foliage.h): cards bent along their length, textures painted
// with the oak's shape painter (parts.h).
#include "shapes/foliage.h"

#include <cmath>

#include "core/error.h"
#include "core/random.h"
#include "shapes/parts.h"

namespace qf {
namespace {

using namespace shape_parts;

// A card bent along its length: `segments` quads whose centre line runs from `root` along
// c(f) = root + length (dir f + bend f^2), f = 0..1 (so `bend`, a vector in length units, curves
// it: down for a drooping branch, outwards for a grass blade), `width` across along unit
// `across` (perpendicular to dir). Texture u runs u0..u1 across, v from 1 at the root to 0 at
// the tip (add_leaf's convention). Normals are across x tangent, and the winding agrees with them.
struct BentCard {
  Vec3f root, dir, bend, across;
  double length = 1, width = 0.1;
  float u0 = 0, u1 = 1;
  int segments = 3;
  std::uint32_t material = 1;
};
void add_bent_card(TriangleMesh& mesh, const BentCard& c) {
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  const Vec3f half = c.across * static_cast<float>(0.5 * c.width);
  for (int i = 0; i <= c.segments; ++i) {
    const float f = static_cast<float>(i) / static_cast<float>(c.segments);
    const Vec3f centre = c.root + (c.dir * f + c.bend * (f * f)) * static_cast<float>(c.length);
    const Vec3f normal = normalized(cross(c.across, c.dir + c.bend * (2 * f)));
    for (const Vec3f& p : {centre - half, centre + half}) mesh.positions.push_back(p), mesh.normals.push_back(normal);
  }
  for (int i = 0; i < c.segments; ++i) {
    const auto l0 = base + static_cast<std::uint32_t>(2 * i), r0 = l0 + 1, l1 = l0 + 2, r1 = l0 + 3;
    const float v0 = 1 - static_cast<float>(i) / static_cast<float>(c.segments), v1 = 1 - static_cast<float>(i + 1) / static_cast<float>(c.segments);
    mesh.triangles.push_back({l0, r0, r1});
    mesh.corner_uvs.push_back({Vec2f{c.u0, v0}, Vec2f{c.u1, v0}, Vec2f{c.u1, v1}});
    mesh.triangles.push_back({l0, r1, l1});
    mesh.corner_uvs.push_back({Vec2f{c.u0, v0}, Vec2f{c.u1, v1}, Vec2f{c.u0, v1}});
    mesh.triangle_materials.insert(mesh.triangle_materials.end(), 2, c.material);
  }
}

// Needles along a twig from (x, y) in direction `angle`, `length` texels long: pairs every 2.2
// texels, 6-9 texels long, 50-70 degrees off the twig towards its tip, tapering to a point, in dark
// greens (the draws in this order, per needle: its length, its angle, its tone).
void paint_needles(TextureImage& t, SplitMix64& random, double x, double y, double angle, double length) {
  const double ca = std::cos(angle), sa = std::sin(angle);
  for (double s = 2; s < length; s += 2.2)
    for (int side : {-1, 1}) {
      PaintedShape needle;
      needle.length = 6 + 3 * random.uniform() * (1 - 0.5 * s / length);  // shorter towards the tip
      needle.angle = angle + side * (50 + 20 * random.uniform()) * kPi / 180;
      needle.tone = 0.7 + 0.5 * random.uniform();
      needle.half_span = 1.1;
      needle.rgb = {34, 78, 38};
      needle.cx = x + ca * s + 0.5 * needle.length * std::cos(needle.angle);
      needle.cy = y + sa * s + 0.5 * needle.length * std::sin(needle.angle);
      paint_shape(t, needle, [](double v) { return 1 - 0.8 * v; });  // v = 0 at the twig
    }
}

// A conifer's branch card, 128 x 128: a twig up the middle from the stalk (the bottom, texture
// v = 1) to the tip, side twigs alternating left and right at 45-60 degrees towards the tip,
// longest below the middle (an ovate spray), all covered in needles. Cut-away texels stay
// transparent black, as the oak's cards leave them.
TextureImage needle_card_texture(SplitMix64& random) {
  constexpr int kSide = 128;
  TextureImage t{kSide, kSide, std::vector<std::uint8_t>(kSide * kSide * 4, 0)};
  const auto twig = [&](double x, double y, double angle, double length, double thickness) {
    PaintedShape s;
    s.cx = x + 0.5 * length * std::cos(angle), s.cy = y + 0.5 * length * std::sin(angle);
    s.angle = angle, s.length = length, s.half_span = thickness, s.rgb = {88, 62, 40};
    paint_shape(t, s, [](double v) { return 1 - 0.5 * v; });  // v = 0 at its base
  };
  // 1. The twigs: the main one from the bottom up (angle -90 degrees: towards y = 0), then 14 side twigs.
  constexpr int kSideTwigs = 14;
  twig(64, 127, -kPi / 2, 124, 2.2);
  struct Twig {
    double x, y, angle, length;
  };
  std::vector<Twig> twigs{{64, 127, -kPi / 2, 124}};
  for (int k = 0; k < kSideTwigs; ++k) {
    const double along = (k + 0.5) / kSideTwigs;  // 0 at the stalk, 1 at the tip
    const int side = k % 2 ? 1 : -1;
    const double angle = -kPi / 2 + side * (45 + 15 * random.uniform()) * kPi / 180;
    const double length = (14 + 50 * std::sin(kPi * std::pow(1 - along, 0.8))) * (0.85 + 0.15 * random.uniform());
    const double y = 120 - 112 * along;
    twig(64, y, angle, length, 1.2);
    twigs.push_back({64, y, angle, length});
  }
  // 2. Needles over them, so that the twigs show only between needles.
  for (const Twig& w : twigs) paint_needles(t, random, w.x, w.y, w.angle, w.length);
  return t;
}

// Grass: 8 columns of 16 texels, each a blade from base (bottom, v = 1) to tip, full width to 35%
// below the tip and then pointed, shades from dark green (column 0) to straw yellow (column 7).
TextureImage grass_atlas(SplitMix64& random) {
  constexpr int kSide = 128, kColumns = 8;
  TextureImage t{kSide, kSide, std::vector<std::uint8_t>(kSide * kSide * 4, 0)};
  for (int c = 0; c < kColumns; ++c) {
    const double s = static_cast<double>(c) / (kColumns - 1);
    PaintedShape blade;
    blade.cx = 16 * c + 8, blade.cy = 64, blade.angle = kPi / 2, blade.length = 126, blade.half_span = 6.5;
    blade.rgb = {45 + 140 * s, 112 + 58 * s, 30 + 45 * s};
    blade.tone = 0.9 + 0.2 * random.uniform();
    paint_shape(t, blade, [](double v) { return v > 0.35 ? 1.0 : v / 0.35; });  // v = 0 at the tip
  }
  return t;
}

}  // namespace

TriangleMesh generate_conifer(const ConiferOptions& options) {
  if (options.cards == 0 || options.cards > 100000) throw UsageError("a conifer needs 1..100000 cards");
  SplitMix64 random(options.seed);
  TriangleMesh mesh;
  // 1. Materials: bark, and the branch card (cut out by alpha, double-sided).
  add_plant_materials(mesh, random);
  mesh.textures[1] = needle_card_texture(random);
  mesh.materials[1].name = "needles";
  // 2. The trunk, nearly to the top.
  const double height = 5 + random.uniform(), crown_base = 0.12 * height, reach = 0.32 * height * (0.9 + 0.2 * random.uniform());
  add_tube(mesh, {0, 0, 0}, {0, 1, 0}, 0.97 * height, 0.13, 0.02);
  // 3. Tiers of branch cards, about 8 to a tier, from the crown's base to near the top: each
  //    leaves the trunk a little upwards and droops (more in the lower tiers, as boughs sag with
  //    length), its length following the cone. Each tier turns by the golden angle.
  const std::size_t tiers = std::max<std::size_t>(1, options.cards / 8);
  for (std::size_t t = 0; t < tiers; ++t) {
    const std::size_t first = t * options.cards / tiers, last = (t + 1) * options.cards / tiers;
    const double f = (t + 0.5) / tiers, y = crown_base + (0.93 * height - crown_base) * f;  // f: 0 low .. 1 top
    for (std::size_t b = first; b < last; ++b) {
      const double around = 2.39996 * t + 2 * kPi * (b - first + 0.4 * random.uniform()) / (last - first);
      const double rise = (5 + 12 * random.uniform()) * kPi / 180, roll = (random.uniform() - 0.5) * 50 * kPi / 180;
      const Vec3f out = vec(std::cos(around), 0, std::sin(around));
      BentCard card;
      card.dir = normalized(out * static_cast<float>(std::cos(rise)) + Vec3f{0, static_cast<float>(std::sin(rise)), 0});
      const Vec3f flat = normalized(cross(card.dir, Vec3f{0, 1, 0}));  // horizontal, across the bough
      card.across = normalized(flat * static_cast<float>(std::cos(roll)) + cross(card.dir, flat) * static_cast<float>(std::sin(roll)));
      card.length = (0.12 + reach * std::pow(1 - f, 0.95)) * (0.85 + 0.3 * random.uniform());
      card.width = 0.55 * card.length + 0.08;
      card.bend = vec(0, -(0.2 + 0.3 * (1 - f)) * (0.8 + 0.4 * random.uniform()), 0);
      card.root = vec(0, y + 0.1 * (random.uniform() - 0.5) * height / tiers, 0) + out * 0.04f;
      add_bent_card(mesh, card);
    }
  }
  // 4. The leader: two crossed upright cards on top.
  for (const Vec3f across : {Vec3f{1, 0, 0}, Vec3f{0, 0, 1}}) {
    BentCard leader;
    leader.root = vec(0, 0.9 * height, 0), leader.dir = {0, 1, 0}, leader.bend = {0, 0, 0}, leader.across = across;
    leader.length = 0.14 * height, leader.width = 0.3, leader.segments = 1;
    add_bent_card(mesh, leader);
  }
  return mesh;
}

TriangleMesh generate_grass(const GrassOptions& options) {
  if (options.blades == 0 || options.blades > 100000) throw UsageError("a grass clump needs 1..100000 blades");
  SplitMix64 random(options.seed);
  TriangleMesh mesh;
  // 1. One material: the blade atlas, cut out by alpha, seen from both sides.
  mesh.textures = {grass_atlas(random)};
  mesh.materials = {card_material("grass", 0)};
  // 2. Blades from a disc, the outer ones shorter, leaning and curving further out (as a clump
  //    splays); most in greens, fewer straw-coloured (the column drawn skewed towards 0).
  constexpr double kRadius = 0.12;
  for (std::size_t i = 0; i < options.blades; ++i) {
    const double r = kRadius * std::sqrt(random.uniform()), around = 2 * kPi * random.uniform();
    const Vec3f out = vec(std::cos(around), 0, std::sin(around));
    const double lean = (5 + 35 * (r / kRadius) * (0.5 + 0.5 * random.uniform())) * kPi / 180;
    const double twist = (random.uniform() - 0.5) * 60 * kPi / 180, curl = 0.15 + 0.35 * random.uniform();
    BentCard blade;
    blade.root = out * static_cast<float>(r);
    blade.dir = normalized(out * static_cast<float>(std::sin(lean)) + Vec3f{0, static_cast<float>(std::cos(lean)), 0});
    const Vec3f side = normalized(cross(Vec3f{0, 1, 0}, out));  // the blade's face looks outwards
    blade.across = normalized(side * static_cast<float>(std::cos(twist)) + cross(blade.dir, side) * static_cast<float>(std::sin(twist)));
    blade.bend = out * static_cast<float>(curl) - Vec3f{0, static_cast<float>(0.5 * curl), 0};
    blade.length = (0.3 + 0.5 * random.uniform()) * (1 - 0.3 * r / kRadius);
    blade.width = 0.012 + 0.008 * random.uniform();
    const int column = std::min(7, static_cast<int>(8 * std::pow(random.uniform(), 1.6)));
    blade.u0 = column / 8.0f, blade.u1 = (column + 1) / 8.0f;
    blade.segments = 4;
    blade.material = 0;
    add_bent_card(mesh, blade);
  }
  return mesh;
}

}  // namespace qf
