// The render methods' draw lists (runtime_gl/blend_order): pure CPU, no GL context.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "runtime_gl/blend_order.h"
#include "runtime_gl/camera.h"
#include "core/error.h"

namespace qf::render {
namespace {

// A row of n quads along +x at depth z = -k (k-th is further from an eye at +z), all facing +z
// except those listed; neighbours: i ~ i+1.
ImpostorScene row_scene(int n, std::set<int> facing_away = {}) {
  ImpostorScene s;
  for (int k = 0; k < n; ++k) {
    Item it;
    it.first_vertex = static_cast<std::uint32_t>(6 * k);
    it.vertex_count = 6;
    it.center = {static_cast<float>(k), 0, -static_cast<float>(k)};
    it.normal = facing_away.count(k) ? Vec3f{0, 0, -1} : Vec3f{0, 0, 1};
    s.items.push_back(it);
  }
  s.offsets.push_back(0);
  for (int k = 0; k < n; ++k) {
    if (k > 0) s.neighbors.push_back(static_cast<std::uint32_t>(k - 1));
    if (k + 1 < n) s.neighbors.push_back(static_cast<std::uint32_t>(k + 1));
    s.offsets.push_back(static_cast<std::uint32_t>(s.neighbors.size()));
  }
  return s;
}

const Vec3f kEye{0, 0, 10};

TEST(BlendOrder, OverlapFollowsThePapersFigure10) {
  const ImpostorScene s = row_scene(4);
  const std::vector<DrawOp> ops = plan_draws(Method::kOverlap, s, kEye);
  // d0 (nearest): colour d0, colour its neighbour d1, lock d0; d1: colour d2, lock d1; ...
  const std::vector<DrawOp> expected{{0, Pass::kColor}, {1, Pass::kColor}, {0, Pass::kLock}, {2, Pass::kColor},
                                     {1, Pass::kLock},  {3, Pass::kColor}, {2, Pass::kLock}, {3, Pass::kLock}};
  ASSERT_EQ(ops.size(), expected.size());
  for (std::size_t i = 0; i < ops.size(); ++i) {
    EXPECT_EQ(ops[i].item, expected[i].item) << i;
    EXPECT_EQ(ops[i].pass, expected[i].pass) << i;
  }
}

TEST(BlendOrder, OverlapDrawsEachFacingItemOnceAndLocksAfterItsColour) {
  const ImpostorScene s = row_scene(7, {2, 5});
  const std::vector<DrawOp> ops = plan_draws(Method::kOverlap, s, kEye);
  std::vector<int> colour(7, 0), lock(7, 0);
  for (const DrawOp& op : ops) {
    if (op.pass == Pass::kColor) {
      EXPECT_EQ(lock[op.item], 0) << "colour after lock, item " << op.item;
      ++colour[op.item];
    } else {
      ASSERT_EQ(op.pass, Pass::kLock);
      EXPECT_EQ(colour[op.item], 1) << "locked before drawn, item " << op.item;
      ++lock[op.item];
    }
  }
  for (int k = 0; k < 7; ++k) {
    const int expected = (k == 2 || k == 5) ? 0 : 1;  // back faces: neither drawn nor locked (culled)
    EXPECT_EQ(colour[k], expected) << k;
    EXPECT_EQ(lock[k], expected) << k;
  }
}

TEST(BlendOrder, SortIsByDistanceWithTiesByIndex) {
  ImpostorScene s = row_scene(3);
  s.offsets.clear();  // no graph: plain sorted lock
  s.neighbors.clear();
  s.items[0].center = {0, 0, -5};  // now the furthest
  s.items[2].center = {1, 0, -1};  // same distance as item 1 ({1, 0, -1})
  const std::vector<DrawOp> ops = plan_draws(Method::kOverlap, s, kEye);
  const std::vector<std::uint32_t> colours = [&] {
    std::vector<std::uint32_t> c;
    for (const DrawOp& op : ops)
      if (op.pass == Pass::kColor) c.push_back(op.item);
    return c;
  }();
  EXPECT_EQ(colours, (std::vector<std::uint32_t>{1, 2, 0}));
}

TEST(BlendOrder, BackfaceMethodsGoBackToFrontAndDarkenBackFaces) {
  const ImpostorScene s = row_scene(4, {1});
  for (Method m : {Method::kBackfaceHard, Method::kBackfaceSoft}) {
    const std::vector<DrawOp> ops = plan_draws(m, s, kEye);
    ASSERT_EQ(ops.size(), 4u);
    EXPECT_EQ(ops[0].item, 3u);
    EXPECT_EQ(ops[3].item, 0u);
    EXPECT_EQ(ops[2].item, 1u);
    EXPECT_EQ(ops[2].pass, m == Method::kBackfaceHard ? Pass::kDarkenHard : Pass::kDarkenSoft);
    EXPECT_EQ(ops[0].pass, Pass::kAddNoDepth);
  }
}

TEST(BlendOrder, TwoPassWritesOffsetDepthFirst) {
  const std::vector<DrawOp> ops = plan_draws(Method::kTwoPass, row_scene(3), kEye);
  ASSERT_EQ(ops.size(), 6u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(ops[static_cast<std::size_t>(i)].pass, Pass::kDepthOffset);
  for (int i = 3; i < 6; ++i) EXPECT_EQ(ops[static_cast<std::size_t>(i)].pass, Pass::kColor);
}

TEST(BlendOrder, DoubleSidedLevelsDrawQuadsSeenFromBehind) {
  ImpostorScene s = row_scene(4);
  s.items[1].normal = s.items[1].normal * -1.0f;  // faces away from the eye
  for (Method m : {Method::kOverlap, Method::kTwoPass, Method::kBlendAll, Method::kNoBlend}) {
    s.double_sided = false;
    for (const DrawOp& op : plan_draws(m, s, kEye)) EXPECT_NE(op.item, 1u) << method_name(m);
    s.double_sided = true;
    std::size_t drawn = 0;
    for (const DrawOp& op : plan_draws(m, s, kEye)) drawn += op.item == 1u && op.pass != Pass::kLock && op.pass != Pass::kDepthOffset;
    EXPECT_EQ(drawn, 1u) << method_name(m);
  }
  EXPECT_TRUE(plan_draws(Method::kEngine, s, kEye).empty());  // draw_engine draws the materials
  EXPECT_FALSE(is_additive(Method::kEngine));
  EXPECT_TRUE(is_additive(Method::kOverlap));
}

TEST(BlendOrder, MethodNamesRoundTrip) {
  for (const std::string& n : method_names()) EXPECT_EQ(method_name(method_from_name(n)), n);
  EXPECT_THROW(method_from_name("painter"), UsageError);
}

TEST(Camera, FramedSphereFitsAndViewsAreSpreadOverTheSphere) {
  const Sphere s{{1, 2, 3}, 2};
  const Camera c = orbit_camera(s, orbit_direction(30, 20), 0, 400, 200);
  // The sphere touches the narrower (vertical) field of view: sin(15 deg) = r / d.
  EXPECT_NEAR(length(c.eye - c.target) * std::sin(15.0 * 3.14159265358979 / 180), 2.0, 1e-4);
  EXPECT_LT(c.near_plane, length(c.eye - c.target) - 2);
  EXPECT_GT(c.far_plane, length(c.eye - c.target) + 2);
  // 26 directions: unit, and no two closer than 25 degrees.
  for (int i = 0; i < 26; ++i) {
    EXPECT_NEAR(length(sphere_direction(i, 26)), 1.0, 1e-5);
    for (int j = 0; j < i; ++j) EXPECT_LT(dot(sphere_direction(i, 26), sphere_direction(j, 26)), std::cos(25.0 * 3.14159265358979 / 180));
  }
  // The view matrix takes the target onto the -z axis at the eye distance.
  const Mat4 v = c.view();
  const Vec3f t = c.target;
  const float z = v[2] * t.x + v[6] * t.y + v[10] * t.z + v[14];
  const float x = v[0] * t.x + v[4] * t.y + v[8] * t.z + v[12];
  EXPECT_NEAR(x, 0, 1e-4);
  EXPECT_NEAR(z, -length(c.eye - c.target), 1e-3);
}

TEST(Camera, OctahedralFramesCoverTheSphereAsTheMapFolds) {
  // A 5 x 5 grid: the centre looks down from +Y, the edges' middles along the horizontal axes, and
  // the four corners fold onto -Y (scripts/octahedral_peer.py reads the same layout).
  auto near = [](Vec3f a, Vec3f b) { return length(a - b) < 1e-5; };
  EXPECT_TRUE(near(octahedral_direction(2, 2, 5), {0, 1, 0}));
  EXPECT_TRUE(near(octahedral_direction(0, 2, 5), {-1, 0, 0}));
  EXPECT_TRUE(near(octahedral_direction(4, 2, 5), {1, 0, 0}));
  EXPECT_TRUE(near(octahedral_direction(2, 0, 5), {0, 0, -1}));
  EXPECT_TRUE(near(octahedral_direction(2, 4, 5), {0, 0, 1}));
  for (int c : {0, 4})
    for (int r : {0, 4}) EXPECT_TRUE(near(octahedral_direction(c, r, 5), {0, -1, 0}));
  // Below the equator: frame (0, 1) of 5 is (u, v) = (-1, -0.5), folded to (x, z) = (-0.5, 0), y = -0.5.
  const Vec3f below = octahedral_direction(0, 1, 5);
  EXPECT_LT(below.y, 0);
  EXPECT_LT(below.x, 0);
  // 8 x 8: unit directions, none farther than 40 degrees from its grid neighbour, all distinct but
  // where the map's border folds onto itself (frame (0, r) is frame (0, 7 - r), (c, 0) is (7 - c, 0),
  // and the four corners are -Y).
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c) {
      const Vec3f d = octahedral_direction(c, r, 8);
      EXPECT_NEAR(length(d), 1.0, 1e-5);
      if (c + 1 < 8) {
        EXPECT_GT(dot(d, octahedral_direction(c + 1, r, 8)), std::cos(40.0 * 3.14159265358979 / 180));
      }
      for (int r2 = 0; r2 < 8; ++r2)
        for (int c2 = 0; c2 < 8; ++c2) {
          const bool corners = (c == 0 || c == 7) && (r == 0 || r == 7) && (c2 == 0 || c2 == 7) && (r2 == 0 || r2 == 7);
          const bool folded = ((c == 0 || c == 7) && c2 == c && r2 == 7 - r) || ((r == 0 || r == 7) && r2 == r && c2 == 7 - c);
          if ((r2 != r || c2 != c) && !corners && !folded) {
            EXPECT_LT(dot(d, octahedral_direction(c2, r2, 8)), 0.9999f);
          }
        }
    }
}

}  // namespace
}  // namespace qf::render
