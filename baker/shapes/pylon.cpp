// The power pylon (pylon.h): a four-legged tapering lattice of square beams (parts.h add_beam).
#include "shapes/pylon.h"

#include <cmath>
#include <vector>

#include "core/random.h"
#include "shapes/parts.h"

namespace qf {
namespace {

using shape_parts::add_beam;
using shape_parts::vec;

// The tower's proportions, drawn from the seed (the draws in the order of the fields).
struct PylonShape {
  double height, base, waist_y, waist, top_y, top;  // half-widths base, waist and top at y = 0, waist_y, top_y
  int lower_panels, upper_panels, arm_tiers;
  double arm_reach;

  // Half the width of the tower's square section at height y: straight legs below and above the waist.
  double half_at(double y) const {
    return y <= waist_y ? base + (waist - base) * y / waist_y : waist + (top - waist) * (y - waist_y) / (top_y - waist_y);
  }
  // Corner c (0..3, counter-clockwise seen from above, starting at -x -z) at height y.
  Vec3f corner(double y, int c) const {
    const double h = half_at(y);
    return vec((c == 0 || c == 3) ? -h : h, y, c < 2 ? -h : h);
  }
};

PylonShape draw_shape(SplitMix64& random) {
  PylonShape s;
  s.height = 36 + 8 * random.uniform();
  s.base = s.height * (0.10 + 0.02 * random.uniform());
  s.waist_y = 0.62 * s.height, s.waist = 0.028 * s.height;
  s.top_y = 0.9 * s.height, s.top = 0.022 * s.height;
  s.lower_panels = 6 + static_cast<int>(random.next() % 3);
  s.upper_panels = 5 + static_cast<int>(random.next() % 2);
  s.arm_tiers = 2 + static_cast<int>(random.next() % 2);
  s.arm_reach = s.height * (0.13 + 0.05 * random.uniform());
  return s;
}

// Panel boundaries from the ground to the top: the splayed lower panels shorter towards the waist
// (as their faces narrow, so that the braces keep their angle), the upper ones even.
std::vector<double> panel_levels(const PylonShape& s) {
  std::vector<double> y;
  for (int k = 0; k <= s.lower_panels; ++k) y.push_back(s.waist_y * (1 - std::pow(1 - static_cast<double>(k) / s.lower_panels, 1.35)));
  for (int k = 1; k <= s.upper_panels; ++k) y.push_back(s.waist_y + (s.top_y - s.waist_y) * k / s.upper_panels);
  return y;
}

class Builder {
 public:
  explicit Builder(TriangleMesh& mesh) : mesh_(mesh) {}
  void beam(Vec3f a, Vec3f b, double width, std::uint32_t material = 0) {
    add_beam(mesh_, a, b, static_cast<float>(width));
    mesh_.triangle_materials.insert(mesh_.triangle_materials.end(), 12, material);
  }

 private:
  TriangleMesh& mesh_;
};

// One cross arm on side `side` (-1: towards -x, +1: +x) between panel boundaries yb and yt: four
// chords from the body's face to a tip `reach` out at yb, laced at 4 stations by zigzag struts in
// its sides and bottom, and the insulator string hanging from the tip.
void add_arm(Builder& b, const PylonShape& s, double yb, double yt, double reach, int side) {
  const double hb = s.half_at(yb), ht = s.half_at(yt), chord = s.height / 260, strut = s.height / 320;
  const Vec3f tip = vec(side * (hb + reach), yb, 0);
  const Vec3f inner[4] = {vec(side * hb, yb, -hb), vec(side * hb, yb, hb), vec(side * ht, yt, -ht), vec(side * ht, yt, ht)};
  for (const Vec3f& p : inner) b.beam(p, tip, chord);
  const auto at = [&](int chord_index, double f) { return inner[chord_index] + (tip - inner[chord_index]) * static_cast<float>(f); };
  constexpr int kStations = 4;
  for (int k = 0; k < kStations; ++k) {
    const double f0 = static_cast<double>(k) / kStations, f1 = static_cast<double>(k + 1) / kStations;
    b.beam(at(0, f0), at(2, f1), strut);  // the z- side
    b.beam(at(1, f0), at(3, f1), strut);  // the z+ side
    b.beam(at(k % 2, f0), at(1 - k % 2, f1), strut);  // the bottom
    if (k > 0) b.beam(at(0, f0), at(1, f0), strut), b.beam(at(2, f0), at(3, f0), strut);
  }
  b.beam(tip, tip - vec(0, 0.09 * s.height, 0), s.height / 160, 1);
}

}  // namespace

TriangleMesh generate_pylon(const PylonOptions& options) {
  SplitMix64 random(options.seed);
  const PylonShape s = draw_shape(random);
  const std::vector<double> y = panel_levels(s);
  TriangleMesh mesh;
  Builder b(mesh);
  const double leg = s.height / 200, brace = s.height / 320, chord = s.height / 260;
  // 1. The body: per panel, the four legs, a ring of horizontals at its top and an X on each face.
  for (std::size_t p = 0; p + 1 < y.size(); ++p)
    for (int c = 0; c < 4; ++c) {
      const int c1 = (c + 1) % 4;
      b.beam(s.corner(y[p], c), s.corner(y[p + 1], c), leg);
      b.beam(s.corner(y[p + 1], c), s.corner(y[p + 1], c1), brace);
      b.beam(s.corner(y[p], c), s.corner(y[p + 1], c1), brace);
      b.beam(s.corner(y[p], c1), s.corner(y[p + 1], c), brace);
    }
  // 2. Plan bracing across the waist, where the legs bend: what keeps the section square.
  b.beam(s.corner(s.waist_y, 0), s.corner(s.waist_y, 2), brace);
  b.beam(s.corner(s.waist_y, 1), s.corner(s.waist_y, 3), brace);
  // 3. Cross arms on both sides at every other boundary down from the top; with three tiers the
  //    middle one reaches furthest (as double-circuit towers space their phases).
  const int top = static_cast<int>(y.size()) - 1;
  for (int i = 0; i < s.arm_tiers; ++i) {
    const double reach = s.arm_reach * (s.arm_tiers == 3 && i == 1 ? 1.12 : 1 - 0.06 * i);
    for (int side : {-1, 1}) add_arm(b, s, y[static_cast<std::size_t>(top - 1 - 2 * i)], y[static_cast<std::size_t>(top - 2 * i)], reach, side);
  }
  // 4. The earth-wire peak: the corners to an apex, and a short arm across it for the earth wires.
  const Vec3f apex = vec(0, s.height, 0);
  for (int c = 0; c < 4; ++c) b.beam(s.corner(s.top_y, c), apex, chord);
  const double wire_y = 0.5 * (s.top_y + s.height), wire_reach = 0.06 * s.height;
  b.beam(vec(-wire_reach, wire_y, 0), vec(wire_reach, wire_y, 0), chord);
  for (int side : {-1, 1}) b.beam(vec(side * wire_reach, wire_y, 0), apex, brace);
  // 5. Materials: weathered galvanised steel and glazed insulators, both opaque.
  SurfaceMaterial steel, insulator;
  steel.name = "steel", insulator.name = "insulator";
  steel.base_color = {0.42f, 0.44f, 0.45f, 1};
  insulator.base_color = {0.12f, 0.22f, 0.16f, 1};
  insulator.roughness = 0.3f;
  mesh.materials = {steel, insulator};
  return mesh;
}

}  // namespace qf
