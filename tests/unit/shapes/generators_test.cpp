// The generated assets of issue 49 (conifer, grass, pylon, machine): same seed same bytes, another
// seed other bytes, and the property that makes each what it is: alpha-masked textured cards
// (conifer, grass), beams ~1/200 of the height (pylon), inner parts hidden by the housing except
// through its openings (machine). The CLI test `generated_shapes` validates the files.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "gltf/glb.h"
#include "shapes/foliage.h"
#include "shapes/machine.h"
#include "shapes/pylon.h"

namespace qf {
namespace {

// Seeds of these tests; scripts/bench.sh far uses others, so that the benchmark's assets are unseen.
constexpr std::uint64_t kSeed = 2, kOtherSeed = 3;

std::vector<std::uint8_t> conifer_glb(std::uint64_t seed) {
  ConiferOptions o;
  o.seed = seed;
  return encode_textured_mesh_glb(generate_conifer(o));
}
std::vector<std::uint8_t> grass_glb(std::uint64_t seed) {
  GrassOptions o;
  o.seed = seed;
  return encode_textured_mesh_glb(generate_grass(o));
}
std::vector<std::uint8_t> pylon_glb(std::uint64_t seed) {
  PylonOptions o;
  o.seed = seed;
  return encode_textured_mesh_glb(generate_pylon(o));
}
std::vector<std::uint8_t> machine_glb(std::uint64_t seed) {
  MachineOptions o;
  o.seed = seed;
  return encode_machine_glb(generate_machine(o));
}

TEST(GeneratedShapes, SameSeedSameBytesOtherSeedOtherBytes) {
  for (const auto make : {conifer_glb, grass_glb, pylon_glb, machine_glb}) {
    const std::vector<std::uint8_t> a = make(kSeed), b = make(kSeed), c = make(kOtherSeed);
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);
  }
}

// Fractions of a texture's texels that are cut away (alpha 0) and that are cut away but not black.
struct Cutaway {
  double cut = 0, coloured = 0;
};
Cutaway cutaway(const TextureImage& t) {
  std::size_t cut = 0, coloured = 0, n = t.rgba.size() / 4;
  for (std::size_t i = 0; i < n; ++i)
    if (t.rgba[4 * i + 3] == 0) ++cut, coloured += (t.rgba[4 * i] | t.rgba[4 * i + 1] | t.rgba[4 * i + 2]) != 0;
  return {static_cast<double>(cut) / n, static_cast<double>(coloured) / n};
}

// Mean RGB of the opaque texels in columns x0..x1 of a texture.
std::array<double, 3> mean_opaque(const TextureImage& t, int x0 = 0, int x1 = -1) {
  if (x1 < 0) x1 = t.width;
  std::array<double, 3> sum{0, 0, 0};
  double n = 0;
  for (int y = 0; y < t.height; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * t.width + x) * 4];
      if (p[3] < 128) continue;
      for (int c = 0; c < 3; ++c) sum[static_cast<std::size_t>(c)] += p[c];
      n += 1;
    }
  for (double& s : sum) s /= std::max(n, 1.0);
  return sum;
}

TEST(GeneratedShapes, ConiferIsAConeOfMaskedNeedleCards) {
  ConiferOptions o;
  o.seed = kSeed;
  const TriangleMesh m = generate_conifer(o);
  // 1. Cards: material 1, alpha-tested, double-sided, a texture with cut-away texels left black.
  ASSERT_EQ(m.materials.size(), 2u);
  const SurfaceMaterial& needles = m.materials[1];
  EXPECT_EQ(needles.alpha_mode, AlphaMode::kMask);
  EXPECT_TRUE(needles.double_sided);
  ASSERT_GE(needles.texture, 0);
  const TextureImage& card = m.textures[static_cast<std::size_t>(needles.texture)];
  const Cutaway cut = cutaway(card);
  EXPECT_GT(cut.cut, 0.3);  // a spray of needles, not a filled quad
  EXPECT_LT(cut.cut, 0.9);
  EXPECT_EQ(cut.coloured, 0);
  // 2. Dark green needles.
  const std::array<double, 3> rgb = mean_opaque(card);
  EXPECT_GT(rgb[1], rgb[0]);
  EXPECT_GT(rgb[1], rgb[2]);
  EXPECT_LT(rgb[1], 110);
  // 3. The cards: 3 quads bent along each of o.cards, and the leader's 2 quads.
  const auto card_triangles = std::count(m.triangle_materials.begin(), m.triangle_materials.end(), 1u);
  EXPECT_EQ(static_cast<std::size_t>(card_triangles), 6 * o.cards + 4);
  // 4. A cone: the cards' horizontal reach in the lowest quarter of the height is more than twice
  //    that in the top quarter, and each card droops (its tip below its root).
  const Bounds b = m.bounds();
  const float h = b.max.y;
  double low = 0, high = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3f p = m.positions[v];
    const double r = std::hypot(p.x, p.z);
    if (p.y < b.min.y + 0.35f * h && p.y > 0.1f * h) low = std::max(low, r);
    if (p.y > 0.75f * h) high = std::max(high, r);
  }
  EXPECT_GT(low, 2 * high);
  EXPECT_GT(h, 4.5f);
}

TEST(GeneratedShapes, GrassIsBentMaskedBladesFromGreenToStraw) {
  GrassOptions o;
  o.seed = kSeed;
  const TriangleMesh m = generate_grass(o);
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].alpha_mode, AlphaMode::kMask);
  EXPECT_TRUE(m.materials[0].double_sided);
  EXPECT_EQ(m.triangles.size(), 8 * o.blades);  // 4 quads a blade
  ASSERT_EQ(m.textures.size(), 1u);
  const TextureImage& atlas = m.textures[0];
  EXPECT_GT(cutaway(atlas).cut, 0.2);  // blades cut to their pointed shape
  EXPECT_EQ(cutaway(atlas).coloured, 0);
  // The atlas's first column is green, its last straw: red catches up with green.
  const std::array<double, 3> green = mean_opaque(atlas, 0, 16), straw = mean_opaque(atlas, 112, 128);
  EXPECT_LT(green[0] / green[1], 0.5);
  EXPECT_GT(straw[0] / straw[1], 0.9);
  // Blades of varying heights (each blade's 10 vertices: its tip is the last pair), bending outwards.
  float lowest = 1e9f, highest = 0;
  for (std::size_t blade = 0; blade < o.blades; ++blade) {
    const Vec3f root = m.positions[10 * blade], tip = m.positions[10 * blade + 8];
    lowest = std::min(lowest, tip.y), highest = std::max(highest, tip.y);
    EXPECT_GT(std::hypot(tip.x, tip.z), std::hypot(root.x, root.z) - 0.02f);
  }
  EXPECT_GT(highest - lowest, 0.25f);
}

TEST(GeneratedShapes, PylonBeamsAreAbout1Over200OfItsHeight) {
  for (std::uint64_t seed : {kSeed, kOtherSeed}) {
    PylonOptions o;
    o.seed = seed;
    const TriangleMesh m = generate_pylon(o);
    const float height = m.bounds().max.y - m.bounds().min.y;
    EXPECT_GE(height, 36.0f);
    EXPECT_LE(height, 44.5f);
    // Each beam is 8 corners (add_beam): corners 0 and 1 span its width.
    ASSERT_EQ(m.positions.size() % 8, 0u);
    const std::size_t beams = m.positions.size() / 8;
    EXPECT_GT(beams, 250u);
    float widest = 0, thinnest = 1e9f;
    std::size_t steel_beams = 0;
    for (std::size_t k = 0; k < beams; ++k) {
      const float w = length(m.positions[8 * k] - m.positions[8 * k + 1]);
      if (m.triangle_materials[12 * k] != 0) continue;  // the insulators
      widest = std::max(widest, w), thinnest = std::min(thinnest, w), ++steel_beams;
    }
    EXPECT_NEAR(widest / height, 1.0 / 200, 0.02 / 200);  // the legs
    EXPECT_NEAR(thinnest / height, 1.0 / 320, 0.02 / 320);  // the braces
    EXPECT_LT(steel_beams, beams);  // insulators too
  }
}

// Whether the ray from o along unit d meets triangle (a, b, c) (Moller-Trumbore).
bool hits(Vec3f o, Vec3f d, Vec3f a, Vec3f b, Vec3f c) {
  const Vec3f e1 = b - a, e2 = c - a, p = cross(d, e2);
  const float det = dot(e1, p);
  if (std::fabs(det) < 1e-12f) return false;
  const Vec3f s = o - a;
  const float u = dot(s, p) / det;
  if (u < 0 || u > 1) return false;
  const Vec3f q = cross(s, e1);
  const float v = dot(d, q) / det;
  if (v < 0 || u + v > 1) return false;
  return dot(e2, q) / det > 1e-4f;  // not the triangle the ray starts on
}

TEST(GeneratedShapes, MachineInnerPartsAreHiddenButForItsOpenings) {
  MachineOptions o;
  o.seed = kSeed;
  const Machine machine = generate_machine(o);
  const auto housing = std::find_if(machine.parts.begin(), machine.parts.end(), [](const MachinePart& p) { return p.name == "housing"; });
  ASSERT_NE(housing, machine.parts.end());
  // 1. Parts with names of their own, one material each, several of them inside.
  std::set<std::string> names;
  std::size_t inner_parts = 0;
  for (const MachinePart& p : machine.parts) {
    names.insert(p.name);
    EXPECT_EQ(p.mesh.materials.size(), 1u) << p.name;
    inner_parts += p.inner;
  }
  EXPECT_EQ(names.size(), machine.parts.size());
  EXPECT_GE(inner_parts, 4u);
  // 2. Every inner triangle's centroid lies in the cavity; from each, 26 rays (to the cube's
  //    faces, edges and corners) look for a way out past every part (the housing's walls, and
  //    the parts themselves: a gear's far side is hidden by the gear).
  std::vector<Vec3f> directions;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) directions.push_back(normalized(Vec3f{static_cast<float>(x) + 0.01f, static_cast<float>(y) + 0.02f, static_cast<float>(z) + 0.03f}));
  std::vector<std::array<Vec3f, 3>> occluders;
  for (const MachinePart& p : machine.parts)
    for (const Triangle& t : p.mesh.triangles) occluders.push_back({p.mesh.positions[t[0]], p.mesh.positions[t[1]], p.mesh.positions[t[2]]});
  std::size_t inner = 0, seen = 0;
  for (const MachinePart& p : machine.parts) {
    if (!p.inner) continue;
    for (const Triangle& t : p.mesh.triangles) {
      const Vec3f c = (p.mesh.positions[t[0]] + p.mesh.positions[t[1]] + p.mesh.positions[t[2]]) * (1.0f / 3);
      const Bounds& cavity = machine.cavity;
      ASSERT_TRUE(c.x >= cavity.min.x && c.x <= cavity.max.x && c.y >= cavity.min.y && c.y <= cavity.max.y && c.z >= cavity.min.z &&
                  c.z <= cavity.max.z) << p.name;
      ++inner;
      const bool out = std::any_of(directions.begin(), directions.end(), [&](Vec3f d) {
        return std::none_of(occluders.begin(), occluders.end(), [&](const std::array<Vec3f, 3>& w) { return hits(c, d, w[0], w[1], w[2]); });
      });
      seen += out;
    }
  }
  EXPECT_GT(inner, 1000u);  // most of the assembly's triangles
  EXPECT_GT(seen, 0u);      // the window shows some
  EXPECT_LT(static_cast<double>(seen) / inner, 0.3) << seen << " of " << inner;  // 0.19 (seed 2)
  // 3. The file: a root "machine" whose children are the parts' nodes, each a mesh of its own.
  tinygltf::Model g;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const std::vector<std::uint8_t> bytes = encode_machine_glb(machine);
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&g, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()))) << err;
  EXPECT_EQ(g.meshes.size(), machine.parts.size());
  std::set<std::string> nodes;
  for (const tinygltf::Node& n : g.nodes) nodes.insert(n.name);
  EXPECT_TRUE(nodes.count("machine") && nodes.count("housing") && nodes.count("gear_large") && nodes.count("motor"));
}

}  // namespace
}  // namespace qf
