// Support rectangles (paper 3.1): plane, axes, extent with splat radii, approximation error.
#include <gtest/gtest.h>

#include <cmath>

#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "analysis/analysis.h"
#include "domains/merge.h"
#include "primitives/support.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

// One basis function holding every point with weight 1.
SparseMatrix all_in_one(std::size_t n) {
  std::vector<std::int32_t> outer(n + 1), inner(n, 0);
  std::vector<double> values(n, 1.0);
  for (std::size_t i = 0; i <= n; ++i) outer[i] = static_cast<std::int32_t>(i);
  return from_rows(static_cast<Eigen::Index>(n), 1, outer, inner, values);
}

PointSet grid_on_plane(float noise) {
  // 41 x 21 points on [0,2] x [0,1] at z = 0.5, radius 0.05, normals +z; z jittered by +-noise.
  PointSet p;
  for (int y = 0; y <= 20; ++y)
    for (int x = 0; x <= 40; ++x) {
      const float jitter = noise * (((x * 7 + y * 13) % 5) / 2.0f - 1.0f);  // -1 .. 1 in steps of 0.5
      p.positions.push_back({0.05f * x, 0.05f * y, 0.5f + jitter});
      p.normals.push_back({0, 0, 1});
      p.radii.push_back(0.05f);
    }
  return p;
}

TEST(Support, PlanarDomain) {
  const PointSet p = grid_on_plane(0);
  const SparseMatrix psi = all_in_one(p.size());
  const std::vector<SupportRect> r = support_rectangles(p.positions, p.normals, p.radii, psi, make_domains(psi));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_NEAR(r[0].normal.z, 1.0f, 1e-6f);
  EXPECT_NEAR(std::fabs(r[0].axis_u.x), 1.0f, 1e-6f);  // the long side
  EXPECT_NEAR(r[0].half_u, 1.0f + 0.05f, 1e-5f);        // points plus their splat radius
  EXPECT_NEAR(r[0].half_v, 0.5f + 0.05f, 1e-5f);
  EXPECT_NEAR(r[0].center.x, 1.0f, 1e-5f);
  EXPECT_NEAR(r[0].center.z, 0.5f, 1e-5f);
  EXPECT_NEAR(r[0].error, 0.0, 1e-6);
  EXPECT_EQ(r[0].points, p.size());
  // Right-handed frame.
  EXPECT_NEAR(dot(cross(r[0].axis_u, r[0].axis_v), r[0].normal), 1.0f, 1e-6f);
  // A margin of 1 mean radius on every side.
  SupportOptions o;
  o.margin = 1.0f;
  EXPECT_NEAR(support_rectangles(p.positions, p.normals, p.radii, psi, make_domains(psi), o)[0].half_u, 1.1f, 1e-5f);
}

TEST(Support, ErrorIsTheMeanDistanceToThePlane) {
  const PointSet p = grid_on_plane(0.01f);
  const SparseMatrix psi = all_in_one(p.size());
  const SupportRect r = support_rectangles(p.positions, p.normals, p.radii, psi, make_domains(psi))[0];
  double expect = 0, mean_z = 0;
  for (const Vec3f& x : p.positions) mean_z += x.z;
  mean_z /= p.size();
  for (const Vec3f& x : p.positions) expect += std::fabs(x.z - mean_z);
  expect /= p.size();
  EXPECT_NEAR(r.error, expect, 1e-3 * expect);
  EXPECT_NEAR(r.relative_error, expect / 0.05, 1e-3);
}

TEST(Support, ProjectedRadiiShrinkTiltedSplats) {
  PointSet p = grid_on_plane(0);
  for (Vec3f& n : p.normals) n = normalized({0.6f, 0, 0.8f});  // tilted 37 degrees: |n . z| = 0.8
  const SparseMatrix psi = all_in_one(p.size());
  SupportOptions o;
  o.projected_radii = true;
  const SupportRect r = support_rectangles(p.positions, p.normals, p.radii, psi, make_domains(psi), o)[0];
  EXPECT_NEAR(r.half_u, 1.0f + 0.8f * 0.05f, 1e-5f);
}

TEST(Support, OctahedronFaces) {
  // The merged octahedron (paper fig. 1c): 8 rectangles on the 8 faces.
  const PointSet p = generate_shape("octahedron");
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  std::vector<SupportRect> rects;
  for_each_basis(h, h.level_count() - 1, {}, [&](std::size_t, const SparseMatrix& psi) {
    if (psi.cols() > 64) return;  // the fine levels cannot merge down to 8
    const SparseMatrix merged = merge_domains(psi, p.positions);
    if (merged.cols() == 8 && rects.empty()) rects = support_rectangles(p.positions, p.normals, p.radii, merged, make_domains(merged));
  });
  ASSERT_EQ(rects.size(), 8u);
  for (const SupportRect& r : rects) {
    // The face normal is (+-1, +-1, +-1)/sqrt(3), on the side of the rectangle's centre.
    const Vec3f face{r.center.x < 0 ? -1.f : 1.f, r.center.y < 0 ? -1.f : 1.f, r.center.z < 0 ? -1.f : 1.f};
    EXPECT_GT(dot(r.normal, normalized(face)), std::cos(3.0f * 3.14159265f / 180.0f));
    EXPECT_LT(r.relative_error, 0.5);  // domains reach a little over the edges
  }
}

TEST(Support, NormalsWithoutInputPointOutward) {
  PointSet p = generate_shape("sphere", {8000, 2});
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  const SparseMatrix psi = basis_at_level(h, h.level_count() - 3);
  const std::vector<SupportRect> rects = support_rectangles(p.positions, {}, p.radii, psi, make_domains(psi));
  ASSERT_GT(rects.size(), 10u);
  for (const SupportRect& r : rects) EXPECT_GT(dot(r.normal, normalized(r.center)), 0.9f);
}

}  // namespace
}  // namespace qf
