// The sample tree (tree.h).
#include "shapes/tree.h"

#include <cmath>

#include "core/color.h"
#include "core/error.h"
#include "core/random.h"

namespace qf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Bark: brown with vertical grooves and a little noise, repeating around the trunk.
TextureImage bark_texture(SplitMix64& random) {
  TextureImage t{64, 64, std::vector<std::uint8_t>(64 * 64 * 4)};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double groove = 0.75 + 0.25 * std::sin(x * 2 * kPi / 8.0 + 0.8 * std::sin(y * 2 * kPi / 32.0));
      const double shade = groove * (0.85 + 0.15 * random.uniform());
      std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * 64 + x) * 4];
      p[0] = static_cast<std::uint8_t>(110 * shade), p[1] = static_cast<std::uint8_t>(78 * shade);
      p[2] = static_cast<std::uint8_t>(50 * shade), p[3] = 255;
    }
  return t;
}

// A leaf: a pointed oval (u across, v along from the stalk at v = 1 to the tip at v = 0) with a
// lighter midrib; alpha 0 outside it, so a MASK material cuts the quad to the leaf's shape. The
// cut-away texels keep a leaf green (as texture artists dilate colour into them): black there
// would bleed into the leaf's edge in an engine's mipmaps and darken the tree at a distance.
TextureImage leaf_texture() {
  TextureImage t{64, 64, std::vector<std::uint8_t>(64 * 64 * 4, 0)};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double u = (x + 0.5) / 32.0 - 1, v = (y + 0.5) / 64.0;      // u in -1..1, v in 0..1
      const double half_width = 0.95 * std::sin(kPi * v) * std::sqrt(v);  // widest past the middle
      if (std::fabs(u) > half_width) {
        std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * 64 + x) * 4];
        p[0] = 50, p[1] = 110, p[2] = 34, p[3] = 0;
        continue;
      }
      const double rib = std::fabs(u) < 0.06 ? 1.25 : 1.0;
      const double shade = (0.7 + 0.3 * (1 - std::fabs(u) / std::max(half_width, 1e-6))) * rib;
      std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * 64 + x) * 4];
      p[0] = static_cast<std::uint8_t>(std::min(255.0, 60 * shade)), p[1] = static_cast<std::uint8_t>(std::min(255.0, 130 * shade));
      p[2] = static_cast<std::uint8_t>(std::min(255.0, 40 * shade)), p[3] = 255;
    }
  return t;
}

Vec3f vec(double x, double y, double z) { return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)}; }

// Any two unit vectors perpendicular to unit d and to each other.
void frame(Vec3f d, Vec3f& a, Vec3f& b) {
  a = normalized(cross(d, std::fabs(d.y) < 0.9f ? Vec3f{0, 1, 0} : Vec3f{1, 0, 0}));
  b = cross(d, a);
}

// A tapered tube from `from` along unit `dir`, `length` long, radius r0 -> r1, with the bark's
// texture coordinates (u around, twice; v along, one repeat per unit).
void add_tube(TriangleMesh& mesh, Vec3f from, Vec3f dir, double length, double r0, double r1, int kSides = 10, int kRings = 6) {
  Vec3f a, b;
  frame(dir, a, b);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (int i = 0; i <= kRings; ++i) {
    const double f = static_cast<double>(i) / kRings, r = r0 + (r1 - r0) * f;
    for (int k = 0; k < kSides; ++k) {
      const double angle = 2 * kPi * k / kSides;
      const Vec3f radial = a * static_cast<float>(std::cos(angle)) + b * static_cast<float>(std::sin(angle));
      mesh.positions.push_back(from + dir * static_cast<float>(length * f) + radial * static_cast<float>(r));
      mesh.normals.push_back(radial);
    }
  }
  for (int i = 0; i < kRings; ++i)
    for (int k = 0; k < kSides; ++k) {
      const auto v = [&](int ring, int side) { return base + static_cast<std::uint32_t>(ring * kSides + (side % kSides)); };
      const float u0 = 2.0f * static_cast<float>(k) / kSides, u1 = 2.0f * static_cast<float>(k + 1) / kSides;
      const float v0 = static_cast<float>(length * i / kRings), v1 = static_cast<float>(length * (i + 1) / kRings);
      mesh.triangles.push_back({v(i, k), v(i, k + 1), v(i + 1, k + 1)});
      mesh.corner_uvs.push_back({Vec2f{u0, v0}, Vec2f{u1, v0}, Vec2f{u1, v1}});
      mesh.triangles.push_back({v(i, k), v(i + 1, k + 1), v(i + 1, k)});
      mesh.corner_uvs.push_back({Vec2f{u0, v0}, Vec2f{u1, v1}, Vec2f{u0, v1}});
      mesh.triangle_materials.insert(mesh.triangle_materials.end(), 2, 0u);
    }
}

// A leaf quad at `at` facing unit `n`, its stalk end pointing along `along` (in the leaf's plane).
void add_leaf(TriangleMesh& mesh, Vec3f at, Vec3f n, Vec3f along, float length, float width) {
  const Vec3f across = normalized(cross(n, along));
  const Vec3f up = cross(across, n);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  const Vec3f corners[4] = {at - across * (0.5f * width), at + across * (0.5f * width),
                            at + across * (0.5f * width) + up * length, at - across * (0.5f * width) + up * length};
  for (const Vec3f& c : corners) mesh.positions.push_back(c), mesh.normals.push_back(n);
  // Texture v = 1 at the stalk (the quad's base), 0 at the tip. Wound counter-clockwise seen from
  // the side `n` points to (across x up = -n, so the corners go 0 3 2 1): engines take the winding
  // for the front, and flip a double-sided back face's normal; a winding against NORMAL would
  // leave every leaf lit from behind, ambient only.
  mesh.triangles.push_back({base, base + 3, base + 2});
  mesh.corner_uvs.push_back({Vec2f{0, 1}, Vec2f{0, 0}, Vec2f{1, 0}});
  mesh.triangles.push_back({base, base + 2, base + 1});
  mesh.corner_uvs.push_back({Vec2f{0, 1}, Vec2f{1, 0}, Vec2f{1, 1}});
  mesh.triangle_materials.insert(mesh.triangle_materials.end(), 2, 1u);
}

// Bark (repeating) and leaves (cut out by alpha, seen from both sides): materials 0 and 1.
void add_plant_materials(TriangleMesh& mesh, SplitMix64& random) {
  mesh.textures = {bark_texture(random), leaf_texture()};
  SurfaceMaterial bark;
  bark.name = "bark";
  bark.texture = 0;
  SurfaceMaterial leaf;
  leaf.name = "leaf";
  leaf.texture = 1;
  leaf.wrap_s = leaf.wrap_t = TextureWrap::kClampToEdge;
  leaf.alpha_mode = AlphaMode::kMask;
  leaf.double_sided = true;
  mesh.materials = {bark, leaf};
}

// A unit direction uniform on the sphere (the draws in this order: its height, then its azimuth).
struct Direction {
  double x, y, z;
};
Direction random_direction(SplitMix64& random) {
  const double z = 2 * random.uniform() - 1, phi = 2 * kPi * random.uniform();
  return {std::sqrt(1 - z * z) * std::cos(phi), z, std::sqrt(1 - z * z) * std::sin(phi)};
}

// A point uniform in a ball of `radius` about the origin (a direction, then the distance), its
// height scaled by `squash` and raised by `lift`: where a plant's leaves gather about a tip.
Vec3f random_in_ball(SplitMix64& random, double radius, double squash, double lift) {
  const Direction d = random_direction(random);
  const double r = radius * std::cbrt(random.uniform());
  return vec(d.x * r, d.y * r * squash + lift, d.z * r);
}

// A leaf at at + offset facing a random direction, its stalk towards `at`, min_size..min_size +
// size_span long (the draws in this order: the normal, then the size).
void add_random_leaf(TriangleMesh& mesh, SplitMix64& random, Vec3f at, Vec3f offset, double min_size, double size_span) {
  const Direction d = random_direction(random);
  const Vec3f n = vec(d.x, d.y, d.z);
  Vec3f along = offset - n * dot(offset, n);  // outward from `at`, in the leaf's plane
  if (dot(along, along) < 1e-8f) frame(n, along, along);
  const float size = static_cast<float>(min_size + size_span * random.uniform());
  add_leaf(mesh, at + offset, n, normalized(along), size, 0.6f * size);
}

// A branch from `from` along `dir` and, while `depth` lasts, 2-3 children from its upper half,
// each 0.6-0.75 as long and 0.55 as thick, turned 30-60 degrees away and upwards (the draws in this
// order: the count, then per child its place, turn and length). Twigs are 6-sided tubes of 2 rings.
void add_branch(TriangleMesh& mesh, SplitMix64& random, Vec3f from, Vec3f dir, double length, double radius, int depth) {
  const bool twig = depth == 0;
  add_tube(mesh, from, dir, length, radius, 0.6 * radius, twig ? 6 : 8, twig ? 2 : 4);
  if (depth == 0) return;
  Vec3f a, b;
  frame(dir, a, b);
  const int children = 2 + static_cast<int>(random.next() % 2);
  for (int c = 0; c < children; ++c) {
    const double at = 0.5 + 0.5 * random.uniform(), turn = (0.5 + 0.5 * random.uniform()) * kPi / 3,
                 around = 2 * kPi * (c + random.uniform()) / children;
    const Vec3f side = a * static_cast<float>(std::cos(around)) + b * static_cast<float>(std::sin(around));
    const Vec3f child = normalized(dir * static_cast<float>(std::cos(turn)) + side * static_cast<float>(std::sin(turn)) + Vec3f{0, 0.2f, 0});
    add_branch(mesh, random, from + dir * static_cast<float>(length * at), child, length * (0.6 + 0.15 * random.uniform()),
               0.55 * radius * (1 - 0.4 * at), depth - 1);
  }
}

// A card of leaves: `count` leaves (the leaf's pointed oval, ~1/5 of the card long, turned at
// random) scattered over a 128 x 128 image, greens varied per leaf. Texels outside every leaf
// are transparent black, as many exported game textures leave them (no colour dilated into the
// cut-away): an engine's mips and bilinear filter then mix that black into the leaves' edges.
TextureImage leaf_card_texture(SplitMix64& random, int count) {
  constexpr int kSide = 128;
  TextureImage t{kSide, kSide, std::vector<std::uint8_t>(kSide * kSide * 4, 0)};
  for (int l = 0; l < count; ++l) {
    const double cx = 12 + (kSide - 24) * random.uniform(), cy = 12 + (kSide - 24) * random.uniform();
    const double angle = 2 * kPi * random.uniform(), length = 20 + 10 * random.uniform();
    const double tone = 0.75 + 0.5 * random.uniform();
    const double ca = std::cos(angle), sa = std::sin(angle);
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
        const double v = (dx * ca + dy * sa) / length + 0.5, u = (-dx * sa + dy * ca) / (0.5 * length);  // v 0..1 along
        if (v < 0 || v > 1) continue;
        const double half_width = 0.95 * std::sin(kPi * v) * std::sqrt(v);
        if (std::fabs(u) > half_width) continue;
        const double shade = tone * (0.75 + 0.25 * (1 - std::fabs(u) / std::max(half_width, 1e-6)));
        std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * kSide + x) * 4];
        p[0] = static_cast<std::uint8_t>(std::min(255.0, 55 * shade)), p[1] = static_cast<std::uint8_t>(std::min(255.0, 105 * shade));
        p[2] = static_cast<std::uint8_t>(std::min(255.0, 30 * shade)), p[3] = 255;
      }
  }
  return t;
}

}  // namespace

TriangleMesh generate_card_tree(const CardTreeOptions& options) {
  if (options.cards == 0 || options.cards > 100000) throw UsageError("a card tree needs 1..100000 cards");
  SplitMix64 random(options.seed);
  TriangleMesh mesh;
  // 1. Materials: bark, and the leaf card (cut out by alpha, seen from both sides).
  add_plant_materials(mesh, random);
  mesh.textures[1] = leaf_card_texture(random, 40);
  // 2. The trunk, and limbs leaving it upwards in a spiral, branching twice.
  add_tube(mesh, {0, 0, 0}, {0, 1, 0}, 2.4, 0.18, 0.08);
  std::vector<Vec3f> tips;
  for (int i = 0; i < 6; ++i) {
    const double angle = 2.4 * i + 0.5 * random.uniform(), height = 1.4 + 1.0 * i / 5;
    const Vec3f dir = normalized(vec(std::cos(angle), 0.6 + 0.4 * random.uniform(), std::sin(angle)));
    const double length = 1.0 + 0.3 * random.uniform();
    const Vec3f from{0, static_cast<float>(height), 0};
    add_branch(mesh, random, from, dir, length, 0.06, 1);
    tips.push_back(from + dir * static_cast<float>(length));
  }
  tips.push_back({0, 2.4f, 0});
  // 3. Cards about the tips, each facing a random direction, 0.6-0.9 units a side, within 0.8 of
  //    its tip: a crown of ~2.4 units across, as game trees build theirs from a few hundred cards.
  for (std::size_t c = 0; c < options.cards; ++c) {
    const Vec3f tip = tips[static_cast<std::size_t>(random.next() % tips.size())];
    const Vec3f offset = random_in_ball(random, 0.8, 0.7, 0.1);
    const Direction d = random_direction(random);
    const Vec3f n = vec(d.x, d.y, d.z);
    Vec3f along, other;
    frame(n, along, other);
    const float size = static_cast<float>(0.6 + 0.3 * random.uniform());
    add_leaf(mesh, tip + offset - along * (0.5f * size), n, along, size, size);
  }
  return mesh;
}

TriangleMesh generate_bare_tree(std::uint64_t seed) {
  SplitMix64 random(seed);
  TriangleMesh mesh;
  mesh.textures = {bark_texture(random)};
  SurfaceMaterial bark;
  bark.name = "bark";
  bark.texture = 0;
  mesh.materials = {bark};
  // The trunk, then 6 limbs in a spiral, each branching four times down to twigs ~0.004 thick
  // (a tree 4 units tall: at 64 px on screen a pixel is ~0.08 units, so twigs are a twentieth of
  // a pixel and the limbs about one).
  add_tube(mesh, {0, 0, 0}, {0, 1, 0}, 2.2, 0.14, 0.07);
  for (int i = 0; i < 6; ++i) {
    const double angle = 2.4 * i + 0.5 * random.uniform(), height = 1.2 + 1.0 * i / 5;
    const Vec3f dir = normalized(vec(std::cos(angle), 0.8 + 0.4 * random.uniform(), std::sin(angle)));
    add_branch(mesh, random, {0, static_cast<float>(height), 0}, dir, 1.0 + 0.3 * random.uniform(), 0.05, 4);
  }
  return mesh;
}

TriangleMesh generate_tree(const TreeOptions& options) {
  if (options.leaves == 0 || options.leaves > 1000000) throw UsageError("a tree needs 1..1000000 leaves");
  SplitMix64 random(options.seed);
  TriangleMesh mesh;
  // 1. Materials: bark and leaves.
  add_plant_materials(mesh, random);
  // 2. The trunk, and branches leaving it upwards in a spiral.
  add_tube(mesh, {0, 0, 0}, {0, 1, 0}, 2.6, 0.16, 0.07);
  constexpr int kBranches = 7;
  std::vector<Vec3f> tips;
  for (int i = 0; i < kBranches; ++i) {
    const double angle = 2.4 * i + 0.5 * random.uniform(), height = 1.3 + 1.2 * i / (kBranches - 1);
    const Vec3f dir = normalized(vec(std::cos(angle), 0.7 + 0.4 * random.uniform(), std::sin(angle)));
    const double length = 0.9 + 0.4 * random.uniform();
    const Vec3f from{0, static_cast<float>(height), 0};
    add_tube(mesh, from, dir, length, 0.06, 0.025);
    tips.push_back(from + dir * static_cast<float>(length));
  }
  tips.push_back({0, 2.6f, 0});
  // 3. Leaves in clusters around the tips: each at a random offset (denser near the tip),
  //    facing a random direction, its stalk towards the tip.
  for (std::size_t l = 0; l < options.leaves; ++l) {
    const Vec3f tip = tips[static_cast<std::size_t>(random.next() % tips.size())];
    add_random_leaf(mesh, random, tip, random_in_ball(random, 0.7, 0.8, 0.15), 0.16, 0.08);
  }
  return mesh;
}

TriangleMesh generate_bush(const BushOptions& options) {
  if (options.leaves == 0 || options.leaves > 1000000) throw UsageError("a bush needs 1..1000000 leaves");
  SplitMix64 random(options.seed);
  TriangleMesh mesh;
  add_plant_materials(mesh, random);
  // 1. Stems fanning out from the ground, leaning 15-55 degrees from the vertical.
  const int stems = 9 + static_cast<int>(random.next() % 6);
  struct Stem {
    Vec3f from, dir;
    double length;
  };
  std::vector<Stem> all;
  for (int i = 0; i < stems; ++i) {
    const double angle = 2 * kPi * (i + 0.5 * random.uniform()) / stems, lean = (15 + 40 * random.uniform()) * kPi / 180;
    const Vec3f dir = vec(std::sin(lean) * std::cos(angle), std::cos(lean), std::sin(lean) * std::sin(angle));
    const Vec3f from = vec(0.08 * std::cos(angle), 0, 0.08 * std::sin(angle));
    const double length = 0.8 + 0.5 * random.uniform();
    add_tube(mesh, from, dir, length, 0.022, 0.008);
    all.push_back({from, dir, length});
  }
  // 2. Leaves along each stem's upper 60%, within 0.22 of it.
  for (std::size_t l = 0; l < options.leaves; ++l) {
    const Stem& s = all[static_cast<std::size_t>(random.next() % all.size())];
    const Vec3f at = s.from + s.dir * static_cast<float>(s.length * (0.4 + 0.6 * random.uniform()));
    add_random_leaf(mesh, random, at, random_in_ball(random, 0.22, 1, 0), 0.07, 0.05);
  }
  return mesh;
}

}  // namespace qf
