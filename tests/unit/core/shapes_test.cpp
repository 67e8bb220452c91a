// The analytic sample shapes lie on their surfaces, carry their colours, and are reproducible.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

TEST(Shapes, OctahedronIsThePapersFigure) {
  const PointSet p = generate_shape("octahedron");
  ASSERT_EQ(p.size(), 16000u);
  ASSERT_TRUE(p.has_normals() && p.has_colors() && p.has_radii());
  std::map<std::tuple<int, int, int>, int> per_color;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3f x = p.positions[i];
    EXPECT_NEAR(std::fabs(x.x) + std::fabs(x.y) + std::fabs(x.z), 1.0f, 1e-5f);
    // The normal is the face's: signs of the position over sqrt(3).
    const Vec3f n = p.normals[i];
    EXPECT_NEAR(std::fabs(n.x), 1 / std::sqrt(3.0f), 1e-6f);
    EXPECT_GE(n.x * x.x, 0.0f);
    EXPECT_GE(n.z * x.z, 0.0f);
    ++per_color[{p.colors[i].r, p.colors[i].g, p.colors[i].b}];
  }
  ASSERT_EQ(per_color.size(), 8u);  // one colour per face
  for (const auto& kv : per_color) EXPECT_EQ(kv.second, 2000);
}

TEST(Shapes, SurfacesAndNormals) {
  ShapeOptions o;
  o.points = 4000;
  const PointSet sphere = generate_shape("sphere", o);
  for (std::size_t i = 0; i < sphere.size(); ++i) {
    EXPECT_NEAR(length(sphere.positions[i]), 1.0f, 1e-5f);
    EXPECT_GT(dot(sphere.normals[i], sphere.positions[i]), 0.999f);
  }
  const PointSet torus = generate_shape("torus", o);
  for (const Vec3f& x : torus.positions) {
    const float ring = std::sqrt(x.x * x.x + x.y * x.y) - 1.0f;
    EXPECT_NEAR(ring * ring + x.z * x.z, 0.35f * 0.35f, 1e-5f);
  }
  const PointSet cube = generate_shape("cube", o);
  for (std::size_t i = 0; i < cube.size(); ++i) {
    const Vec3f x = cube.positions[i];
    EXPECT_NEAR(std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)}), 1.0f, 1e-6f);
    EXPECT_NEAR(dot(cube.normals[i], x), 1.0f, 1e-6f);  // outward unit normal of the face
  }
  const PointSet crease = generate_shape("crease", o);
  for (const Vec3f& x : crease.positions) EXPECT_TRUE(x.x == 0.0f || x.y == 0.0f);
}

TEST(Shapes, SeededAndReproducible) {
  ShapeOptions o;
  o.points = 1000;
  const PointSet a = generate_shape("torus", o), b = generate_shape("torus", o);
  o.seed = 2;
  const PointSet c = generate_shape("torus", o);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a.positions[i] == b.positions[i]);
  EXPECT_FALSE(a.positions[0] == c.positions[0]);
  EXPECT_THROW(generate_shape("teapot"), UsageError);
}

// The scan-like scene: seen from one station, so its density is uneven (near ground far denser
// than far ground), the building's back and what it hides are missing, every 500th point is an
// outlier, and the rest lie on their surfaces within the range noise.
TEST(Shapes, ScanIsUnevenWithShadowsAndOutliers) {
  ShapeOptions o;
  o.points = 20000;
  const PointSet p = generate_shape("scan", o);
  ASSERT_EQ(p.size(), 20000u);
  ASSERT_TRUE(p.has_normals() && p.has_colors() && p.has_radii());
  std::size_t near_ground = 0, far_ground = 0, back_wall = 0, behind = 0, outliers = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3f x = p.positions[i];
    if (i % 500 == 499) {
      ++outliers;
      continue;
    }
    if (std::fabs(x.y) < 0.02f && p.normals[i].y > 0.99f) {  // ground: equal 1 x 1 patches, near and far from the scanner
      if (x.x > -0.5f && x.x < 0.5f && x.z > 1.5f && x.z < 2.5f) ++near_ground;
      if (x.x > -2.5f && x.x < -1.5f && x.z > -2.0f && x.z < -1.0f) ++far_ground;
      if (x.x > -0.5f && x.x < 0.5f && x.z > -1.6f && x.z < -1.0f) ++behind;  // in the building's shadow
    }
    if (p.normals[i].z < -0.99f) ++back_wall;
  }
  EXPECT_EQ(outliers, 40u);
  EXPECT_GT(near_ground, 5 * std::max<std::size_t>(far_ground, 1));
  EXPECT_GT(far_ground, 0u);
  EXPECT_EQ(back_wall, 0u);
  EXPECT_EQ(behind, 0u);
  // Same seed, same points.
  const PointSet again = generate_shape("scan", o);
  for (std::size_t i = 0; i < p.size(); i += 97) EXPECT_TRUE(p.positions[i] == again.positions[i]);
}

TEST(Shapes, RadiiFollowSpacing) {
  // Octahedron area 8 * sqrt(3)/2 = 6.93; 16000 points give a spacing h = sqrt(area / n) ~ 0.021.
  // For uniform random points the 6th neighbour lies at Gamma(6.5)/Gamma(6)/sqrt(pi) h = 1.35 h
  // on average.
  const PointSet p = generate_shape("octahedron");
  const double h = std::sqrt(8 * std::sqrt(3.0) / 2 / 16000.0);
  double mean = 0;
  for (float r : p.radii) {
    EXPECT_GT(r, 0.4 * h);
    EXPECT_LT(r, 3.5 * h);
    mean += r;
  }
  mean /= p.size();
  EXPECT_GT(mean, 1.2 * h);
  EXPECT_LT(mean, 1.5 * h);
}

}  // namespace
}  // namespace qf
