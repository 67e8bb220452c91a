// Crease-true merged levels (issue 15 item 4; thesis 3.4): with --merge, `--primitives N` counts
// the quads delivered, and on the octahedron and the cube, whatever the seeded sampling, the level
// asked for with N = faces gives one domain per face, each holding >= 95% of its Psi mass on that
// face (the face of a point: the sign pattern of x, y, z; the cube's, its largest coordinate).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <string>

#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "analysis/analysis.h"
#include "domains/domains.h"
#include "domains/merge.h"
#include "pipeline/bake.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

int octahedron_face(Vec3f p) { return (p.x > 0) | (p.y > 0) << 1 | (p.z > 0) << 2; }

int cube_face(Vec3f p) {
  const float ax = std::fabs(p.x), ay = std::fabs(p.y), az = std::fabs(p.z);
  if (ax >= ay && ax >= az) return p.x > 0 ? 0 : 1;
  if (ay >= az) return p.y > 0 ? 2 : 3;
  return p.z > 0 ? 4 : 5;
}

struct Case {
  const char* shape;
  std::size_t points;
  std::uint64_t seed;
};

// The merged level a bake with --merge --primitives <faces> delivers: quads, faces and purity.
void expect_one_quad_per_face(const Case& c, std::size_t faces, int (*face_of)(Vec3f)) {
  SCOPED_TRACE(std::string(c.shape) + " " + std::to_string(c.points) + " points, seed " + std::to_string(c.seed));
  const PointSet generated = generate_shape(c.shape, {c.points, c.seed});
  const PointSet p = permuted(generated, morton_order(generated.positions));  // as the bake orders them
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  BakeOptions o;
  o.merge = true;
  o.primitives = {faces};
  const std::vector<MergedLevel> chosen = choose_merged_levels(h, o, p.positions, p.normals);
  ASSERT_EQ(chosen.size(), 1u);
  const SparseMatrix& psi = chosen[0].psi;
  EXPECT_EQ(chosen[0].quads, faces) << "level " << chosen[0].level;
  ASSERT_EQ(count_domains(psi, o.domains), chosen[0].quads);
  std::vector<std::array<double, 8>> mass(static_cast<std::size_t>(psi.cols()));
  for (auto& m : mass) m.fill(0.0);
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    double sum = 0;
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) {
      ASSERT_GE(it.value(), 0.0);
      sum += it.value();
      mass[static_cast<std::size_t>(it.col())][static_cast<std::size_t>(face_of(p.positions[static_cast<std::size_t>(i)]))] +=
          it.value();
    }
    ASSERT_NEAR(sum, 1.0, 1e-12) << "row " << i << ": merging keeps the partition of unity";
  }
  std::set<std::size_t> owned;
  for (std::size_t d = 0; d < mass.size(); ++d) {
    double total = 0, best = 0;
    std::size_t face = 0;
    for (std::size_t f = 0; f < 8; ++f) {
      total += mass[d][f];
      if (mass[d][f] > best) best = mass[d][f], face = f;
    }
    EXPECT_GE(best, 0.95 * total) << "domain " << d << " of level " << chosen[0].level << ": " << best / total
                                  << " of its Psi mass on face " << face;
    owned.insert(face);
  }
  EXPECT_EQ(owned.size(), faces) << "every face has its own domain";
}

TEST(CreaseTrue, OctahedronGivesEightQuadsOnePerFace) {
  // Seed 2 at 16k points gave 5 quads (the level chosen before merging) and, at the level with 8
  // merged domains, one spanning two faces.
  for (const Case& c : {Case{"octahedron", 8000, 1}, Case{"octahedron", 8000, 4}, Case{"octahedron", 16000, 2},
                        Case{"octahedron", 16000, 6}, Case{"octahedron", 64000, 3}})
    expect_one_quad_per_face(c, 8, octahedron_face);
}

TEST(CreaseTrue, CubeGivesSixQuadsOnePerFace) {
  for (const Case& c : {Case{"cube", 8000, 4}, Case{"cube", 16000, 2}, Case{"cube", 32000, 5}})
    expect_one_quad_per_face(c, 6, cube_face);
}

TEST(CreaseTrue, SliversAreAbsorbedAndCreasesTrimmed) {
  // Octahedron, 8k points: at level 5 the plain merge (thesis 3.4) leaves the 8 faces plus ~15
  // slivers of 3-40 points along the edges, and each face's function reaches past its edges
  // (~5% of its mass on the next faces).
  const PointSet p = generate_shape("octahedron", {8000, 1});
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  ASSERT_GT(h.level_count(), 5u);
  const SparseMatrix psi = basis_at_level(h, 5);
  MergeOptions plain;
  plain.crease_true = false;
  MergeReport before, after;
  const SparseMatrix thesis = merge_domains(psi, p.positions, p.normals, plain, &before);
  const SparseMatrix clean = merge_domains(psi, p.positions, p.normals, {}, &after);
  EXPECT_GT(before.after, 8u);
  EXPECT_EQ(after.after, 8u);
  EXPECT_EQ(after.slivers, before.after - 8);
  EXPECT_GT(after.trimmed, 0u);
  EXPECT_EQ(after.merges, before.merges);
  // Trimmed faces no longer overlap, but the graph keeps the octahedron's 12 edges.
  EXPECT_EQ(after.edges.size(), 12u);
  // Without normals: slivers still go (by mass, into the nearest plane), nothing is trimmed.
  MergeReport no_normals;
  merge_domains(psi, p.positions, std::vector<Vec3f>(), {}, &no_normals);
  EXPECT_EQ(no_normals.trimmed, 0u);
  EXPECT_LT(no_normals.after, before.after);
  // The positions-only overload is the thesis' plain merge.
  MergeReport plain_again;
  EXPECT_EQ(merge_domains(psi, p.positions, {}, &plain_again).cols(), thesis.cols());
  EXPECT_EQ(plain_again.slivers, 0u);
}

}  // namespace
}  // namespace qf
