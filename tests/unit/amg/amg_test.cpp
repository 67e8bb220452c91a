// AMG hierarchy, basis functions and domains (paper 2.3; amg-notes 4): the contracts of every P,
// A_l and Psi_l, coarsening ratios, faces and creases kept apart, determinism.
#include <gtest/gtest.h>
#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "amg/hierarchy_cache.h"
#include "core/hash.h"
#include "analysis/analysis.h"
#include "domains/domains.h"
#include "domains/merge.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

void expect_stochastic(const SparseMatrix& m, const char* what) {
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    double sum = 0;
    for (SparseMatrix::InnerIterator it(m, i); it; ++it) {
      ASSERT_GE(it.value(), 0.0) << what << " row " << i;
      sum += it.value();
    }
    ASSERT_LE(std::fabs(sum - 1.0), 1e-12) << what << " row " << i;
  }
}

void expect_symmetric_zero_rows(const SparseMatrix& a) {
  const SparseMatrix at = a.transpose();
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    double sum = 0, scale = 0;
    for (SparseMatrix::InnerIterator it(a, i); it; ++it) {
      ASSERT_EQ(it.value(), at.coeff(i, it.col()));
      sum += it.value();
      scale = std::max(scale, std::fabs(it.value()));
    }
    ASSERT_LE(std::fabs(sum), 1e-10 * std::max(scale, 1e-300)) << "row " << i;
  }
}

TEST(Amg, ContractsOnEveryLevel) {
  const PointSet p = generate_shape("torus", {20000, 3});
  const SurfaceAnalysis a = analyze_surface(p);
  const AmgHierarchy h = build_hierarchy(a.stiffness);
  ASSERT_GE(h.level_count(), 8u);
  EXPECT_LE(h.levels.back().size, 9u);
  EXPECT_EQ(h.components, 1u);
  for (std::size_t l = 1; l < h.level_count(); ++l) {
    SCOPED_TRACE(l);
    expect_stochastic(h.P[l - 1], "P");
    EXPECT_GE(h.levels[l].ratio, 1.8);
    EXPECT_LE(h.levels[l].ratio, 3.5);
  }
  // The coarse operators, recomputed from Psi (A_l = Psi_l^T A Psi_l), keep symmetry and zero row sums.
  for_each_basis(h, h.level_count() - 1, {}, [&](std::size_t l, const SparseMatrix& psi) {
    SCOPED_TRACE(l);
    ASSERT_EQ(static_cast<std::size_t>(psi.cols()), h.levels[l].size);
    expect_stochastic(psi, "Psi");
    expect_symmetric_zero_rows(symmetrize_zero_row_sums(galerkin_product(a.stiffness, psi), 0.0));
  });
}

TEST(Amg, DeterministicAcrossRunsAndThreads) {
  const PointSet p = generate_shape("sphere", {15000, 4});
  const SurfaceAnalysis a = analyze_surface(p);
  omp_set_num_threads(1);
  const std::uint64_t one = hierarchy_hash(build_hierarchy(a.stiffness));
  omp_set_num_threads(2);
  const AmgHierarchy h = build_hierarchy(a.stiffness);
  EXPECT_EQ(hierarchy_hash(h), one);
  EXPECT_EQ(hierarchy_hash(build_hierarchy(a.stiffness)), one);
  omp_set_num_threads(1);
  const SparseMatrix psi1 = basis_at_level(h, h.level_count() - 2);
  omp_set_num_threads(2);
  const SparseMatrix psi2 = basis_at_level(h, h.level_count() - 2);
  ASSERT_EQ(psi1.nonZeros(), psi2.nonZeros());
  EXPECT_TRUE(std::equal(psi1.valuePtr(), psi1.valuePtr() + psi1.nonZeros(), psi2.valuePtr()));
}

// Octahedron face of a point and its distance (in the face) to the nearest edge.
int face_of(Vec3f p) { return (p.x < 0) | (p.y < 0) << 1 | (p.z < 0) << 2; }
float edge_distance(Vec3f p) {
  return std::min({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) / std::sqrt(2.0f / 3.0f);
}

// Core of every basis function (Psi > 0.5) on a single face, not counting the crease band: the
// points within two sample spacings of an edge, where the classifier is low on both sides.
std::size_t straddling_cores(const SparseMatrix& psi, const PointSet& p, float band,
                             int (*side)(Vec3f), float (*distance)(Vec3f)) {
  const SparseMatrix by_function = psi.transpose();
  std::size_t straddling = 0;
  for (Eigen::Index f = 0; f < by_function.rows(); ++f) {
    std::map<int, int> sides;
    for (SparseMatrix::InnerIterator it(by_function, f); it; ++it) {
      const Vec3f x = p.positions[static_cast<std::size_t>(it.col())];
      if (it.value() > 0.5 && distance(x) > band) ++sides[side(x)];
    }
    straddling += sides.size() > 1;
  }
  return straddling;
}

TEST(Amg, OctahedronFunctionsStayOnTheirFaces) {
  const PointSet p = generate_shape("octahedron");
  const SurfaceAnalysis a = analyze_surface(p);
  const AmgHierarchy h = build_hierarchy(a.stiffness);
  std::size_t level = 0;
  for (std::size_t l = 1; l < h.level_count(); ++l)
    if (h.levels[l].size >= 8) level = l;
  ASSERT_GT(level, 0u);
  const float spacing = std::sqrt(8 * std::sqrt(3.0f) / 2 / float(p.size()));
  const SparseMatrix psi = basis_at_level(h, level);
  EXPECT_EQ(straddling_cores(psi, p, 2 * spacing, face_of, edge_distance), 0u)
      << "level " << level << " with " << h.levels[level].size << " functions";
}

int crease_side(Vec3f p) { return p.y == 0.0f ? 0 : 1; }
float crease_distance(Vec3f p) { return std::max(p.x, p.y); }

TEST(Amg, NoFunctionStraddlesACreaseUntilTheLastLevels) {
  const PointSet p = generate_shape("crease", {20000, 3});
  const SurfaceAnalysis a = analyze_surface(p);
  const AmgHierarchy h = build_hierarchy(a.stiffness);
  const float spacing = std::sqrt(2.0f / 20000.0f);
  ASSERT_GE(h.level_count(), 6u);
  for_each_basis(h, h.level_count() - 3, {}, [&](std::size_t l, const SparseMatrix& psi) {
    EXPECT_EQ(straddling_cores(psi, p, 2 * spacing, crease_side, crease_distance), 0u)
        << "level " << l << " with " << psi.cols() << " functions";
  });
}

TEST(Domains, ThresholdStrictAndGraph) {
  const PointSet p = generate_shape("torus", {10000, 6});
  const SurfaceAnalysis a = analyze_surface(p);
  const AmgHierarchy h = build_hierarchy(a.stiffness);
  const std::size_t level = h.level_count() - 3;
  const SparseMatrix psi = basis_at_level(h, level);
  const Domains d = make_domains(psi);
  ASSERT_EQ(d.count(), static_cast<std::size_t>(psi.cols()));
  // Every point of a domain has weight > tau there, and every such weight puts it in the domain.
  std::size_t memberships = 0;
  for (Eigen::Index i = 0; i < psi.rows(); ++i)
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) memberships += it.value() > 0.05;
  EXPECT_EQ(d.points.size(), memberships);
  for (std::size_t f = 0; f < d.count(); ++f)
    for (std::uint32_t r = d.offsets[f]; r < d.offsets[f + 1]; ++r)
      EXPECT_GT(psi.coeff(d.points[r], static_cast<Eigen::Index>(f)), 0.05);
  EXPECT_GT(d.shared_points, 0u);  // overlapping domains
  ASSERT_FALSE(d.edges.empty());
  for (const auto& e : d.edges) EXPECT_LT(e[0], e[1]);
  // A connected closed surface: the neighbour graph reaches every non-empty domain.
  std::vector<int> seen(d.count(), 0);
  std::vector<std::uint32_t> stack{d.edges[0][0]};
  seen[d.edges[0][0]] = 1;
  while (!stack.empty()) {
    const std::uint32_t x = stack.back();
    stack.pop_back();
    for (const auto& e : d.edges)
      for (int s = 0; s < 2; ++s)
        if (e[s] == x && !seen[e[1 - s]]) seen[e[1 - s]] = 1, stack.push_back(e[1 - s]);
  }
  for (std::size_t f = 0; f < d.count(); ++f) {
    if (d.size(f) > 0) {
      EXPECT_TRUE(seen[f]) << "domain " << f;
    }
  }
  // Strict domains partition the points.
  DomainOptions strict;
  strict.strict = true;
  const Domains s = make_domains(psi, strict);
  EXPECT_EQ(s.points.size(), p.size());
  EXPECT_EQ(s.shared_points, 0u);
  EXPECT_EQ(s.uncovered, 0u);
}

TEST(Amg, DisconnectedPartsAreReported) {
  // Two spheres far apart: two components; coarsening cannot merge them.
  PointSet p = generate_shape("sphere", {4000, 1});
  const PointSet q = generate_shape("sphere", {4000, 2});
  for (std::size_t i = 0; i < q.size(); ++i) {
    p.positions.push_back(q.positions[i] + Vec3f{10, 0, 0});
    p.normals.push_back(q.normals[i]);
  }
  p.colors.clear();
  p.radii.clear();
  const SurfaceAnalysis a = analyze_surface(p);
  const AmgHierarchy h = build_hierarchy(a.stiffness);
  EXPECT_EQ(h.components, 2u);
  EXPECT_GE(h.levels.back().size, 2u);
  expect_stochastic(basis_at_level(h, h.level_count() - 1), "coarsest Psi");
}

}  // namespace
}  // namespace qf

namespace qf {
namespace {

TEST(HierarchyCache, RoundTripsExactlyAndRejectsDamage) {
  const PointSet p = generate_shape("cube", {6000, 5});
  const AnalysisOptions ao;
  const AmgOptions amg;
  const AmgHierarchy h = build_hierarchy(analyze_surface(p, ao).stiffness, amg);
  const std::string dir = ::testing::TempDir() + "qf-cache-test";
  std::filesystem::remove_all(dir);
  const std::string key = hierarchy_cache_key(p, ao, amg);
  std::string why;
  EXPECT_FALSE(load_hierarchy(dir, key, &why));
  EXPECT_EQ(why, "missing");
  const std::vector<Vec3f> normals(p.size(), Vec3f{0, 0.6f, 0.8f});
  // A half-written entry of a killed bake (its pid gone) is removed by the next save; a live
  // process' one stays.
  std::filesystem::create_directories(dir);
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  const std::string stale = dir + "/other.qfamg.tmp-" + std::to_string(child), live = dir + "/mine.qfamg.tmp-" + std::to_string(::getpid());
  std::ofstream(stale) << "half";
  std::ofstream(live) << "half";
  save_hierarchy(dir, key, h, normals);
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_TRUE(std::filesystem::exists(live));
  std::filesystem::remove(live);
  std::vector<Vec3f> normals_back;
  const std::optional<AmgHierarchy> back = load_hierarchy(dir, key, &why, &normals_back);
  ASSERT_TRUE(back);
  ASSERT_EQ(normals_back.size(), normals.size());
  EXPECT_TRUE(normals_back[5] == normals[5]);
  EXPECT_EQ(hierarchy_hash(*back), hierarchy_hash(h));
  EXPECT_EQ(back->components, h.components);
  // Other settings or other points: another key.
  AnalysisOptions k30 = ao;
  k30.neighborhoods.k = 30;
  EXPECT_NE(hierarchy_cache_key(p, k30, amg), key);
  PointSet moved = p;
  moved.positions[17].x += 1e-6f;
  EXPECT_NE(hierarchy_cache_key(moved, ao, amg), key);
  // A truncated or bit-flipped file is detected, never trusted.
  const std::string file = dir + "/" + key + ".qfamg";
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::ofstream(file, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_FALSE(load_hierarchy(dir, key, &why));
  EXPECT_EQ(why, "truncated");
  std::string flipped = bytes;
  flipped[flipped.size() - 100] ^= 0x10;
  std::ofstream(file, std::ios::binary) << flipped;
  EXPECT_FALSE(load_hierarchy(dir, key, &why));
  EXPECT_EQ(why, "corrupt (checksum)");
  // A payload with a valid checksum but a damaged fine_order (not a permutation: the basis would
  // scatter rows out of bounds) is corrupt too (issue 18; fuzz_cache scatters it the same way).
  {
    const std::size_t header = 8 + 4 + key.size() + 16;
    std::string payload = bytes.substr(header);
    const std::size_t order_at = 3 * 8 + h.levels.size() * 24 + 8;  // components, isolated, levels, per level, count
    std::uint32_t first = 0;
    std::memcpy(&first, payload.data() + order_at, 4);
    ASSERT_LT(first, h.levels[0].size);
    const std::uint32_t bad = static_cast<std::uint32_t>(h.levels[0].size) + 7;
    std::memcpy(&payload[order_at], &bad, 4);
    std::string forged = bytes.substr(0, header - 8);
    const std::uint64_t sum = Sha256().update(ByteView(reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size())).digest64();
    forged.append(reinterpret_cast<const char*>(&sum), 8);
    forged += payload;
    EXPECT_FALSE(decode_hierarchy(ByteView(reinterpret_cast<const std::uint8_t*>(forged.data()), forged.size()), key, &why));
    EXPECT_EQ(why, "corrupt");
    // The unforged bytes decode from memory as from the file.
    EXPECT_TRUE(decode_hierarchy(ByteView(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), key, &why));
  }
  std::filesystem::remove_all(dir);
}

TEST(Levels, ByIndexAndByPrimitives) {
  const PointSet p = generate_shape("octahedron");
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  const std::size_t last = h.level_count() - 1;
  EXPECT_EQ(level_by_index(h, 0), 0u);
  EXPECT_EQ(level_by_index(h, -1), last - 1);
  EXPECT_EQ(level_by_index(h, -static_cast<long long>(last)), 0u);
  EXPECT_THROW(level_by_index(h, static_cast<long long>(last) + 1), std::out_of_range);
  EXPECT_EQ(level_by_primitives(h, 1), last);
  EXPECT_EQ(level_by_primitives(h, 1000000), 0u);
  for (std::size_t l = 0; l <= last; ++l) EXPECT_EQ(level_by_primitives(h, h.levels[l].size), l);
}

TEST(Levels, AimedLevelsLandOnTheTargetsAtTwoDensities) {
  // A torus at two densities (as an out-of-core bake's subsample and its whole set): with target
  // sizes both hierarchies hold levels within 3% of each target, the contracts kept.
  AmgOptions amg;
  amg.target_sizes = {300, 100, 30};
  for (std::size_t n : {12000u, 30000u}) {
    SCOPED_TRACE(std::to_string(n) + " points");
    const AmgHierarchy h = build_hierarchy(analyze_surface(generate_shape("torus", {n, 2})).stiffness, amg);
    for (std::size_t t : amg.target_sizes) {
      const std::size_t got = h.levels[level_by_primitives(h, t)].size;
      EXPECT_NEAR(double(got), double(t), 0.03 * double(t)) << "aimed at " << t;
    }
    const SparseMatrix psi = basis_at_level(h, level_by_primitives(h, 30));
    for (Eigen::Index i = 0; i < psi.rows(); ++i) EXPECT_NEAR(psi.row(i).sum(), 1.0, 1e-9);
  }
}

}  // namespace
}  // namespace qf

namespace qf {
namespace {

TEST(Merge, OctahedronEndsWithOneDomainPerFace) {
  // Paper figure 1c: merging flat, parallel, overlapping domains leaves the 8 faces, and the
  // neighbour graph is the octahedron's: 12 edges.
  const PointSet p = generate_shape("octahedron");
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  const float spacing = std::sqrt(8 * std::sqrt(3.0f) / 2 / float(p.size()));
  bool found = false;
  for_each_basis(h, h.level_count() - 1, {}, [&](std::size_t l, const SparseMatrix& psi) {
    MergeReport r;
    const SparseMatrix merged = merge_domains(psi, p.positions, {}, &r);
    expect_stochastic(merged, "merged Psi");
    EXPECT_EQ(straddling_cores(merged, p, 2 * spacing, face_of, edge_distance), 0u) << "level " << l;
    if (r.after != 8) return;
    // One function per face: each face's points mostly (> 0.5) in exactly one function.
    std::map<int, std::set<Eigen::Index>> owners;
    for (Eigen::Index i = 0; i < merged.rows(); ++i)
      for (SparseMatrix::InnerIterator it(merged, i); it; ++it)
        if (it.value() > 0.5 && edge_distance(p.positions[static_cast<std::size_t>(i)]) > 2 * spacing)
          owners[face_of(p.positions[static_cast<std::size_t>(i)])].insert(it.col());
    if (owners.size() != 8) return;
    for (const auto& kv : owners)
      if (kv.second.size() != 1) return;
    EXPECT_EQ(make_domains(merged).edges.size(), 12u) << "level " << l;
    found = true;
  });
  EXPECT_TRUE(found) << "no level merges to exactly one domain per face";
}

}  // namespace
}  // namespace qf

namespace qf {
namespace {

TEST(AmgLarge, MillionPointsGiveTenToFifteenLevels) {
  const PointSet p = generate_shape("torus", {1000000, 1});
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  EXPECT_GE(h.level_count() - 1, 10u);
  EXPECT_LE(h.level_count() - 1, 15u);
  for (std::size_t l = 1; l < h.level_count(); ++l) {
    EXPECT_GE(h.levels[l].ratio, 1.8) << "level " << l;
    EXPECT_LE(h.levels[l].ratio, 3.5) << "level " << l;
    expect_stochastic(h.P[l - 1], "P");
  }
}

}  // namespace
}  // namespace qf
