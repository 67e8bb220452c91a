// The sample tree (tree.h).
#include "shapes/tree.h"

#include <cmath>

#include "core/color.h"
#include "core/error.h"
#include "core/random.h"
#include "shapes/parts.h"

namespace qf {
namespace {

using namespace shape_parts;

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
    PaintedShape leaf;
    leaf.cx = 12 + (kSide - 24) * random.uniform(), leaf.cy = 12 + (kSide - 24) * random.uniform();
    leaf.angle = 2 * kPi * random.uniform(), leaf.length = 20 + 10 * random.uniform(), leaf.half_span = 0.5 * leaf.length;
    leaf.tone = 0.75 + 0.5 * random.uniform();
    leaf.rgb = {55, 105, 30};
    paint_shape(t, leaf, leaf_profile);
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
