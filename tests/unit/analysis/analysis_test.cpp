// Surface analysis (paper 2.1-2.2): classifier, fans and stiffness matrix on analytic shapes with
// known answers, invariants of A, scale invariance, degenerate inputs, thread independence.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "analysis/analysis.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

float median(std::vector<float> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Octahedron face of a point: the signs of its coordinates.
int face_of(Vec3f p) { return (p.x < 0) | (p.y < 0) << 1 | (p.z < 0) << 2; }

// Distance from a point of the octahedron to the nearest edge, measured in its face: the smallest
// |coordinate| over the in-face gradient length sqrt(2/3).
float edge_distance(Vec3f p) {
  return std::min({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) / std::sqrt(2.0f / 3.0f);
}

void expect_stiffness_invariants(const SparseMatrix& a) {
  ASSERT_EQ(a.rows(), a.cols());
  const SparseMatrix at = a.transpose();
  ASSERT_EQ(at.nonZeros(), a.nonZeros());
  for (Eigen::Index i = 0; i < a.outerSize(); ++i) {
    double sum = 0, scale = 0;
    SparseMatrix::InnerIterator t(at, i);
    for (SparseMatrix::InnerIterator it(a, i); it; ++it, ++t) {
      ASSERT_TRUE(std::isfinite(it.value()));
      ASSERT_EQ(it.col(), t.col());
      ASSERT_EQ(it.value(), t.value()) << "A is not exactly symmetric at " << i << "," << it.col();
      sum += it.value();
      scale = std::max(scale, std::fabs(it.value()));
    }
    ASSERT_LE(std::fabs(sum), 1e-12 * std::max(scale, 1e-300)) << "row " << i;
  }
}

TEST(Analysis, OctahedronClassifierSeparatesFacesFromEdges) {
  const PointSet p = generate_shape("octahedron");
  const SurfaceAnalysis a = analyze_surface(p);
  const float h = std::sqrt(8 * std::sqrt(3.0f) / 2 / float(p.size()));  // sample spacing
  std::vector<float> interior, edge;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const float d = edge_distance(p.positions[i]);
    if (d <= h) edge.push_back(a.classifier.value[i]);
    else if (d > 1.2f * a.frames.radius[i]) interior.push_back(a.classifier.value[i]);  // whole neighbourhood in the face
  }
  ASSERT_GT(edge.size(), 500u);
  ASSERT_GT(interior.size(), 1000u);
  EXPECT_GE(median(interior), 100 * median(edge)) << median(interior) << " vs " << median(edge);
}

TEST(Analysis, OctahedronStiffness) {
  const PointSet p = generate_shape("octahedron");
  const SurfaceAnalysis a = analyze_surface(p);
  expect_stiffness_invariants(a.stiffness);
  EXPECT_GE(a.report.mean_fan_size, 5.0);
  EXPECT_LE(a.report.mean_fan_size, 10.0);
  // Coupling across faces is at most 1% of the coupling within faces.
  double same = 0, cross = 0;
  for (Eigen::Index i = 0; i < a.stiffness.outerSize(); ++i)
    for (SparseMatrix::InnerIterator it(a.stiffness, i); it; ++it) {
      if (it.col() == i) continue;
      (face_of(p.positions[i]) == face_of(p.positions[it.col()]) ? same : cross) += std::fabs(it.value());
    }
  EXPECT_LE(cross, 0.01 * same) << "cross " << cross << " same " << same;
}

TEST(Analysis, SmoothSurfacesHaveClosedFansOfFiveToTen) {
  for (const char* shape : {"sphere", "torus"}) {
    SCOPED_TRACE(shape);
    const SurfaceAnalysis a = analyze_surface(generate_shape(shape, {20000, 5}));
    expect_stiffness_invariants(a.stiffness);
    EXPECT_GE(a.report.mean_fan_size, 5.0);
    EXPECT_LE(a.report.mean_fan_size, 10.0);
    EXPECT_EQ(a.report.fans.open, 0u);
    EXPECT_EQ(a.report.fans.empty, 0u);
    EXPECT_EQ(a.report.stiffness.zero_area_triangles, 0u);
    // Without input normals the orientation step must make them all outward on a closed surface.
    PointSet bare = generate_shape(shape, {20000, 5});
    const std::vector<Vec3f> truth = bare.normals;
    bare.normals.clear();
    const SurfaceAnalysis b = analyze_surface(bare);
    std::size_t agree = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) agree += dot(b.frames.normal[i], truth[i]) > 0;
    EXPECT_EQ(agree, truth.size());
    EXPECT_EQ(b.report.normal_components, 1u);
  }
}

TEST(Analysis, PlanarGridGivesDelaunayRings) {
  // A 30x30 grid, spacing 1, in the plane z = 0: every interior point's fan closes, its
  // triangles are right triangles of the grid (Delaunay: no grid point inside a circumcircle),
  // and A is the grid Laplacian: -1/2 cot(90) = 0 for diagonals, couplings to the 4 edge
  // neighbours only.
  PointSet grid;
  const int m = 30;
  for (int y = 0; y < m; ++y)
    for (int x = 0; x < m; ++x) grid.positions.push_back({float(x), float(y), 0});
  const SurfaceAnalysis a = analyze_surface(grid);
  expect_stiffness_invariants(a.stiffness);
  for (int y = 4; y < m - 4; ++y)
    for (int x = 4; x < m - 4; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * m + x);
      ASSERT_EQ(a.fans.count(i), 4u) << "point " << x << "," << y;
      for (std::uint32_t t = a.fans.offsets[i]; t < a.fans.offsets[i + 1]; ++t) {
        const Vec3f pa = grid.positions[a.fans.triangles[t][0]], pb = grid.positions[a.fans.triangles[t][1]];
        const Vec3f pi = grid.positions[i];
        // Right angle at the point: the two legs are grid edges of length 1.
        EXPECT_FLOAT_EQ(length(pa - pi), 1.0f);
        EXPECT_FLOAT_EQ(length(pb - pi), 1.0f);
        EXPECT_FLOAT_EQ(dot(pa - pi, pb - pi), 0.0f);
      }
      // Row i of A: 4 neighbours at C/2 * (cot 45 + cot 45) = C, diagonal 4C (C = 100 on a plane).
      int neighbours = 0;
      for (SparseMatrix::InnerIterator it(a.stiffness, static_cast<Eigen::Index>(i)); it; ++it) {
        if (it.col() == static_cast<Eigen::Index>(i)) {
          EXPECT_NEAR(it.value(), 400.0, 1e-6);
        } else if (it.value() != 0.0) {
          ++neighbours;
          EXPECT_NEAR(it.value(), -100.0, 1e-6);
        }
      }
      EXPECT_EQ(neighbours, 4);
    }
}

TEST(Analysis, CreaseCouplesWeakly) {
  const PointSet p = generate_shape("crease", {20000, 3});
  const SurfaceAnalysis a = analyze_surface(p);
  expect_stiffness_invariants(a.stiffness);
  double same = 0, cross = 0;
  auto side = [&](std::size_t i) { return p.positions[i].y == 0.0f ? 0 : 1; };  // plane y = 0 or x = 0
  for (Eigen::Index i = 0; i < a.stiffness.outerSize(); ++i)
    for (SparseMatrix::InnerIterator it(a.stiffness, i); it; ++it)
      if (it.col() != i) (side(static_cast<std::size_t>(i)) == side(static_cast<std::size_t>(it.col())) ? same : cross) += std::fabs(it.value());
  EXPECT_GT(cross, 0.0);
  EXPECT_LE(cross, 0.01 * same) << "cross " << cross << " same " << same;
}

TEST(Analysis, InvariantUnderUniformScaling) {
  // Scaling by 1e-3 or 1e3 is not exact in binary floating point, so a few near-degenerate fans
  // (four almost cocircular neighbours) may tip the other way; everything else must be the same.
  const PointSet base = generate_shape("torus", {5000, 9});
  const SurfaceAnalysis ref = analyze_surface(base);
  for (float scale : {1e-3f, 1e3f}) {
    SCOPED_TRACE(scale);
    PointSet p = base;
    for (Vec3f& x : p.positions) x = x * scale;
    for (float& r : p.radii) r *= scale;
    const SurfaceAnalysis a = analyze_surface(p);
    std::size_t other_neighbours = 0;  // the k-th neighbour's tie can break the other way
    for (std::size_t i = 0; i < p.size(); ++i)
      other_neighbours += !std::equal(a.neighborhoods.indices.begin() + a.neighborhoods.offsets[i],
                                      a.neighborhoods.indices.begin() + a.neighborhoods.offsets[i + 1],
                                      ref.neighborhoods.indices.begin() + ref.neighborhoods.offsets[i]);
    EXPECT_LE(other_neighbours, p.size() / 200);
    for (std::size_t i = 0; i < p.size(); ++i)
      EXPECT_NEAR(a.classifier.value[i], ref.classifier.value[i], 1e-3f * ref.classifier.value[i]);
    std::vector<char> same_fan(p.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      same_fan[i] = a.fans.count(i) == ref.fans.count(i) &&
                    std::equal(a.fans.triangles.begin() + a.fans.offsets[i], a.fans.triangles.begin() + a.fans.offsets[i + 1],
                               ref.fans.triangles.begin() + ref.fans.offsets[i]);
      differ += !same_fan[i];
    }
    EXPECT_LE(differ, p.size() / 200) << differ << " fans differ";
    // A is dimensionless (cotangents): rows whose fans, and whose neighbours' fans, are all the
    // same hold the same values up to float rounding of the positions.
    std::size_t rows_compared = 0;
    for (Eigen::Index i = 0; i < a.stiffness.outerSize(); ++i) {
      bool comparable = same_fan[static_cast<std::size_t>(i)];
      for (SparseMatrix::InnerIterator it(ref.stiffness, i); it && comparable; ++it)
        comparable = same_fan[static_cast<std::size_t>(it.col())];
      if (!comparable) continue;
      ++rows_compared;
      const double row_scale = ref.stiffness.coeff(i, i);  // the diagonal: the row's largest entry
      SparseMatrix::InnerIterator r(ref.stiffness, i);
      for (SparseMatrix::InnerIterator it(a.stiffness, i); it; ++it, ++r) {
        ASSERT_TRUE(r);
        ASSERT_EQ(it.col(), r.col());
        EXPECT_NEAR(it.value(), r.value(), 1e-4 * row_scale);
      }
    }
    EXPECT_GE(rows_compared, p.size() * 95 / 100);
  }
}

TEST(Analysis, SameResultWithOneAndTwoThreads) {
  PointSet p = generate_shape("cube", {30000, 2});
  p.normals.clear();  // exercise the orientation step too
  omp_set_num_threads(1);
  const SurfaceAnalysis one = analyze_surface(p);
  omp_set_num_threads(2);
  const SurfaceAnalysis two = analyze_surface(p);
  EXPECT_EQ(one.neighborhoods.indices, two.neighborhoods.indices);
  EXPECT_EQ(one.neighborhoods.distances, two.neighborhoods.distances);
  EXPECT_EQ(one.classifier.value, two.classifier.value);
  EXPECT_EQ(one.fans.triangles, two.fans.triangles);
  EXPECT_EQ(one.frames.flipped, two.frames.flipped);
  ASSERT_EQ(one.stiffness.nonZeros(), two.stiffness.nonZeros());
  EXPECT_TRUE(std::equal(one.stiffness.valuePtr(), one.stiffness.valuePtr() + one.stiffness.nonZeros(),
                         two.stiffness.valuePtr()));
  EXPECT_TRUE(std::equal(one.stiffness.innerIndexPtr(), one.stiffness.innerIndexPtr() + one.stiffness.nonZeros(),
                         two.stiffness.innerIndexPtr()));
}

TEST(Analysis, BallNeighbourhoodsWiden) {
  const PointSet p = generate_shape("sphere", {4000, 1});
  AnalysisOptions o;
  o.neighborhoods.k = 10;
  o.neighborhoods.epsilon = 0.15f;  // spacing ~0.056: the 10th neighbour is well inside the ball
  const SurfaceAnalysis a = analyze_surface(p, o);
  EXPECT_GT(a.report.neighborhoods.widened, p.size() * 9 / 10);
  // Brute force for every 20th point: the 10 nearest, or all of B_eps when the 10th is inside it.
  for (std::size_t i = 0; i < p.size(); i += 20) {
    std::vector<std::pair<float, std::uint32_t>> all;
    for (std::size_t j = 0; j < p.size(); ++j)
      if (j != i) all.push_back({length(p.positions[j] - p.positions[i]), static_cast<std::uint32_t>(j)});
    std::sort(all.begin(), all.end());
    std::size_t want = 10;
    if (all[9].first < 0.15f)
      while (want < all.size() && all[want].first <= 0.15f) ++want;
    ASSERT_EQ(a.neighborhoods.count(i), want) << "point " << i;
    for (std::size_t r = 0; r < want; ++r) EXPECT_EQ(a.neighborhoods.indices[a.neighborhoods.offsets[i] + r], all[r].second);
  }
  expect_stiffness_invariants(a.stiffness);
}

// The nearest of a set to other points (the out-of-core links): brute force agrees, ties go to
// the lower index (a grid of points queried at cell centres ties 8 ways), and a far query (an
// outlier) gets its nearest all the same.
TEST(Analysis, NearestPointsAreExactWithTiesByIndex) {
  std::vector<Vec3f> set;
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 20; ++y)
      for (int z = 0; z < 5; ++z) set.push_back({float(x), float(y), float(z)});
  const NearestPoints tree(set);
  std::vector<Vec3f> queries;
  for (int i = 0; i < 300; ++i) queries.push_back({0.5f + float(i % 19), 0.5f + float(i / 19 % 19), 0.5f + float(i % 4)});
  queries.push_back({0.2f, 0.3f, 0.1f});
  queries.push_back({1000, -500, 20});
  constexpr int k = 4;
  std::vector<std::uint32_t> index(queries.size() * k);
  std::vector<float> d2(index.size());
  ASSERT_EQ(tree.nearest(queries.data(), queries.size(), k, index.data(), d2.data()), k);
  for (std::size_t q = 0; q < queries.size(); ++q) {
    std::vector<std::pair<float, std::uint32_t>> all;
    for (std::size_t j = 0; j < set.size(); ++j) {
      const Vec3f v = set[j] - queries[q];
      all.push_back({dot(v, v), static_cast<std::uint32_t>(j)});
    }
    std::sort(all.begin(), all.end());
    for (int r = 0; r < k; ++r) {
      EXPECT_EQ(index[q * k + r], all[r].second) << "query " << q << " rank " << r;
      EXPECT_FLOAT_EQ(d2[q * k + r], all[r].first);
    }
  }
  // Bounded at a squared distance of 2: the same answer where all k lie within it (ties too); past
  // it, infinity and the nearest found; a query with none within it (the far outlier) gets
  // infinity in every slot and a valid index.
  std::vector<std::uint32_t> bounded_index(index.size());
  std::vector<float> bounded_d2(index.size());
  ASSERT_EQ(tree.nearest(queries.data(), queries.size(), k, bounded_index.data(), bounded_d2.data(), 2.0f), k);
  for (std::size_t i = 0; i < index.size(); ++i) {
    if (d2[i] <= 2.0f) {
      EXPECT_EQ(bounded_index[i], index[i]) << i;
      EXPECT_EQ(bounded_d2[i], d2[i]) << i;
    } else {
      EXPECT_TRUE(std::isinf(bounded_d2[i])) << i;
      EXPECT_EQ(bounded_index[i], d2[i - i % k] <= 2.0f ? index[i - i % k] : 0u) << i;
    }
  }
  EXPECT_TRUE(std::isinf(bounded_d2[(queries.size() - 1) * k]));
  // A set smaller than k: every point, nearest first.
  const NearestPoints two({{0, 0, 0}, {1, 0, 0}});
  const Vec3f x{0.9f, 0, 0};
  ASSERT_EQ(two.nearest(&x, 1, k, index.data(), d2.data()), 2);
  EXPECT_EQ(index[0], 1u);
  EXPECT_EQ(index[1], 0u);
}

// Outliers (a scan's strays): points in the air above a sampled plane are found, also where they
// lie among each other, while the plane's sparse part (4x the spacing) and its edges are kept;
// factor 0 and too few points find none; the answer does not depend on the thread count.
TEST(Analysis, OutliersAreStraysNotSparseSurface) {
  std::vector<Vec3f> p;
  for (int x = 0; x < 80; ++x)
    for (int y = 0; y < 80; ++y) p.push_back({float(x), float(y), 0});  // spacing 1
  for (int x = 0; x < 10; ++x)
    for (int y = 0; y < 10; ++y) p.push_back({84.0f + 4 * float(x), 4.0f * float(y), 0});  // spacing 4
  const std::size_t surface = p.size();
  for (int i = 0; i < 40; ++i)  // strays 20-60 above the plane, ~10 apart from each other
    p.push_back({float((i * 37) % 80), float((i * 53) % 80), 20.0f + float(i)});
  OutlierOptions o;
  o.factor = 10;
  const std::vector<char> flags = find_outliers(p, o);
  ASSERT_EQ(flags.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(flags[i], i >= surface ? 1 : 0) << "point " << i;
  omp_set_num_threads(1);
  const std::vector<char> one = find_outliers(p, o);
  omp_set_num_threads(2);
  EXPECT_EQ(one, flags);
  o.factor = 0;
  EXPECT_EQ(find_outliers(p, o), std::vector<char>(p.size(), 0));
  o.factor = 10;
  const std::vector<Vec3f> few{{0, 0, 0}, {1, 0, 0}, {100, 0, 0}};
  EXPECT_EQ(find_outliers(few, o), std::vector<char>(3, 0));
}

TEST(Analysis, DegenerateInputsNeverCrashOrNaN) {
  auto check = [](const PointSet& p, const char* what) {
    SCOPED_TRACE(what);
    const SurfaceAnalysis a = analyze_surface(p);
    EXPECT_EQ(static_cast<std::size_t>(a.stiffness.rows()), p.size());
    for (float c : a.classifier.value) EXPECT_TRUE(std::isfinite(c) && c > 0);
    for (const Vec3f& n : a.frames.normal) EXPECT_TRUE(is_finite(n));
    expect_stiffness_invariants(a.stiffness);
    return a;
  };
  check(PointSet{}, "empty");
  PointSet one;
  one.positions = {{1, 2, 3}};
  EXPECT_EQ(check(one, "one point").report.isolated, 1u);
  PointSet few;
  for (int i = 0; i < 7; ++i) few.positions.push_back({float(i % 3), float(i / 3), 0.1f * i});
  check(few, "fewer points than k");
  PointSet same;
  same.positions.assign(100, {1, 1, 1});
  const SurfaceAnalysis s = check(same, "all identical");
  EXPECT_EQ(s.report.fans.empty, 100u);
  PointSet line;
  for (int i = 0; i < 100; ++i) line.positions.push_back({float(i), 2.0f * i, 0});
  const SurfaceAnalysis l = check(line, "collinear");
  EXPECT_EQ(l.report.fans.empty, 100u);
  PointSet dup = generate_shape("sphere", {2000, 1});
  dup.positions.insert(dup.positions.end(), dup.positions.begin(), dup.positions.begin() + 500);
  dup.normals.clear();
  dup.colors.clear();
  dup.radii.clear();
  const SurfaceAnalysis d = check(dup, "500 duplicated points");
  EXPECT_GT(d.report.fans.duplicates, 0u);
}

}  // namespace
}  // namespace qf
