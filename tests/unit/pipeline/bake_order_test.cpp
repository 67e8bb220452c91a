// The bake depends on the point set, not on the order of its points: a file written in another
// order (a re-export, a shuffled scan) bakes to the same bytes, because the bake sorts the points
// along a Morton curve before anything reads them (pipeline/bake.cpp); only points at exactly the
// same position keep their file order.
#include <gtest/gtest.h>

#include <string>

#include "pipeline/bake.h"
#include "sample/sample.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

void expect_same_bake_when_shuffled(const PointSet& points) {
  BakeOptions o;
  o.primitives = {100, 30};
  const BakeResult a = bake(points, o, "torus");
  const BakeResult b = bake(permuted(points, point_permutation(points.size(), 11)), o, "shuffled torus");
  ASSERT_EQ(a.levels.size(), 2u);
  ASSERT_EQ(b.levels.size(), a.levels.size());
  for (std::size_t l = 0; l < a.levels.size(); ++l) {
    SCOPED_TRACE("level " + std::to_string(a.levels[l].level));
    EXPECT_EQ(b.levels[l].level, a.levels[l].level);
    EXPECT_EQ(b.levels[l].primitives, a.levels[l].primitives);
    EXPECT_TRUE(b.levels[l].glb == a.levels[l].glb) << "the shuffled set's file differs";
  }
}

TEST(BakeOrder, ShuffledPointsBakeTheSameFiles) { expect_same_bake_when_shuffled(generate_shape("torus", {6000, 3})); }

TEST(BakeOrder, ShuffledPointsWithoutNormalsOrRadiiBakeTheSameFiles) {
  // The estimated radii and the orientation by spanning tree (which breaks ties by index) too.
  PointSet points = generate_shape("torus", {6000, 4});
  points.normals.clear();
  points.radii.clear();
  expect_same_bake_when_shuffled(points);
}

TEST(BakeOrder, MortonOrderIsAPermutationThatKeepsNeighboursNear) {
  const PointSet points = generate_shape("sphere", {4000, 5});
  const std::vector<std::uint32_t> order = morton_order(points.positions);
  ASSERT_EQ(order.size(), points.size());
  std::vector<char> seen(points.size(), 0);
  for (std::uint32_t i : order) {
    ASSERT_LT(i, points.size());
    EXPECT_FALSE(seen[i]) << "index " << i << " twice";
    seen[i] = 1;
  }
  // Consecutive points of the sorted set lie far closer than consecutive points of the random one.
  const PointSet sorted = permuted(points, order);
  double random_step = 0, sorted_step = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    random_step += length(points.positions[i] - points.positions[i - 1]);
    sorted_step += length(sorted.positions[i] - sorted.positions[i - 1]);
  }
  EXPECT_LT(sorted_step, 0.2 * random_step);
}

}  // namespace
}  // namespace qf
