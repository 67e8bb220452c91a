// k-nearest neighbours and radius estimation.
#include <gtest/gtest.h>
#include <omp.h>

#include "analysis/neighborhoods.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

TEST(Neighborhoods, GridNeighboursAreExactAndSorted) {
  // A 10x10 grid with spacing 0.5: an interior point's 4 nearest are at 0.5, the next 4 at 0.5*sqrt(2).
  std::vector<Vec3f> grid;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) grid.push_back({0.5f * x, 0.5f * y, 0});
  const Neighborhoods nb = k_nearest(grid, 8);
  ASSERT_EQ(nb.size(), 100u);
  const std::size_t i = 5 * 10 + 5;
  ASSERT_EQ(nb.count(i), 8u);
  for (std::uint32_t r = nb.offsets[i]; r < nb.offsets[i] + 4; ++r) EXPECT_FLOAT_EQ(nb.distances[r], 0.5f);
  for (std::uint32_t r = nb.offsets[i] + 4; r < nb.offsets[i + 1]; ++r) EXPECT_NEAR(nb.distances[r], 0.70710678f, 1e-6f);
  // Ties are ordered by index: the four at 0.5 are (5,4), (4,5), (6,5), (5,6).
  EXPECT_EQ(nb.indices[nb.offsets[i]], 45u);
  EXPECT_EQ(nb.indices[nb.offsets[i] + 1], 54u);
  EXPECT_EQ(nb.indices[nb.offsets[i] + 2], 56u);
  EXPECT_EQ(nb.indices[nb.offsets[i] + 3], 65u);
  for (std::size_t p = 0; p < nb.size(); ++p)
    for (std::uint32_t r = nb.offsets[p]; r < nb.offsets[p + 1]; ++r) EXPECT_NE(nb.indices[r], p);
}

TEST(Neighborhoods, IndependentOfThreadCount) {
  const PointSet p = generate_shape("torus", {5000, 4});
  omp_set_num_threads(1);
  const Neighborhoods one = k_nearest(p.positions, 20);
  omp_set_num_threads(2);
  const Neighborhoods two = k_nearest(p.positions, 20);
  EXPECT_EQ(one.indices, two.indices);
  EXPECT_EQ(one.distances, two.distances);
}

TEST(Neighborhoods, SmallAndDegenerateSets) {
  EXPECT_EQ(k_nearest({}, 5).size(), 0u);
  const Neighborhoods one = k_nearest({{1, 2, 3}}, 5);
  EXPECT_EQ(one.count(0), 0u);
  const Neighborhoods three = k_nearest({{0, 0, 0}, {1, 0, 0}, {3, 0, 0}}, 5);
  EXPECT_EQ(three.count(0), 2u);  // k is capped at n - 1
}

TEST(RadiusEstimate, SpacingAndFallbacks) {
  PointSet grid;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x) grid.positions.push_back({0.1f * x, 0.1f * y, 0});
  EXPECT_EQ(estimate_radii(grid), 400u);
  // interior: 4 neighbours at 0.1, then 4 at 0.1 sqrt(2): the 6th is at 0.1414
  EXPECT_NEAR(grid.radii[10 * 20 + 10], 0.1 * std::sqrt(2.0), 1e-5);
  EXPECT_EQ(estimate_radii(grid), 0u);  // already complete: nothing to do

  PointSet same;
  same.positions.assign(10, {1, 1, 1});
  estimate_radii(same);
  for (float r : same.radii) EXPECT_EQ(r, 1.0f);  // no spacing and no extent: 1
  PointSet dup = grid;
  dup.radii.clear();
  dup.positions.push_back(dup.positions[0]);
  estimate_radii(dup);
  for (float r : dup.radii) EXPECT_GT(r, 0.0f);
}

}  // namespace
}  // namespace qf
