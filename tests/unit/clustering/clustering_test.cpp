// Vertex-clustering LODs (baker/clustering): the displacement bound, consistency when geometry is
// added far away, thin parts kept as thick lines, no degenerate or duplicate output, counts that
// fall with the cell size, determinism, the LOD choice.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "clustering/clustering.h"
#include "gltf/draco.h"
#include "gltf/glb.h"
#include "io/model_io.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

// An open tube of `radius` along X from 0 to `length`, `sides` around, `rings` along.
TriangleMesh tube(float radius, float length, int sides, int rings) {
  TriangleMesh m;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < sides; ++s) {
      const float a = 6.2831853f * static_cast<float>(s) / static_cast<float>(sides);
      m.positions.push_back({length * static_cast<float>(r) / static_cast<float>(rings), radius * std::cos(a), radius * std::sin(a)});
    }
  auto id = [&](int r, int s) { return static_cast<std::uint32_t>(r * sides + (s % sides)); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < sides; ++s) {
      m.triangles.push_back({id(r, s), id(r + 1, s), id(r + 1, s + 1)});
      m.triangles.push_back({id(r, s), id(r + 1, s + 1), id(r, s + 1)});
    }
  return m;
}

TriangleMesh concat(TriangleMesh a, const TriangleMesh& b, Vec3f offset) {
  const auto base = static_cast<std::uint32_t>(a.positions.size());
  for (Vec3f p : b.positions) a.positions.push_back(p + offset);
  for (const Triangle& t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  a.colors.clear();
  return a;
}

ClusterOptions cells(float c) {
  ClusterOptions o;
  o.cell = c;
  return o;
}

TEST(Clustering, DisplacementStaysWithinHalfTheCellDiagonal) {
  const TriangleMesh m = generate_mesh("sphere", 24);
  const VertexGrading g = grade_vertices(m);
  for (float c : {0.15f, 0.3f, 0.6f}) {  // edges are ~0.065 long: every size merges
    for (auto shape : {ClusterOptions::Shape::kCube, ClusterOptions::Shape::kSphere}) {
      ClusterOptions o = cells(c);
      o.shape = shape;
      const LodMesh lod = cluster_mesh(m, g, o);
      const double bound = shape == ClusterOptions::Shape::kCube ? 0.5 * c * std::sqrt(3.0) : 0.5 * c;
      double worst = 0;
      for (std::size_t v = 0; v < m.positions.size(); ++v)
        worst = std::max(worst, double(length(lod.positions[lod.vertex_of[v]] - m.positions[v])));
      EXPECT_LE(worst, bound * (1 + 1e-6)) << "cell " << c;
      EXPECT_GT(worst, 0.3 * bound) << "cell " << c << ": clustering merged something";
    }
  }
}

TEST(Clustering, GeometryFarAwayDoesNotChangeTheRest) {
  // The paper's pot under the tree: a second object does not move the first one's cells.
  const TriangleMesh a = generate_mesh("sphere", 20);
  const TriangleMesh both = concat(a, tube(0.3f, 3.0f, 12, 30), {10, 0, 0});
  for (auto assign : {ClusterOptions::Assign::kNearest, ClusterOptions::Assign::kHeaviest}) {
    ClusterOptions o = cells(0.15f);
    o.assign = assign;
    const LodMesh la = cluster_mesh(a, grade_vertices(a), o), lb = cluster_mesh(both, grade_vertices(both), o);
    std::set<std::array<float, 9>> ta, tb;
    auto key = [](const LodMesh& l, const Triangle& t) {
      std::array<float, 9> k{};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) k[static_cast<std::size_t>(3 * i + j)] = l.positions[t[static_cast<std::size_t>(i)]][j];
      return k;
    };
    for (const Triangle& t : la.triangles) ta.insert(key(la, t));
    for (const Triangle& t : lb.triangles)
      if (lb.positions[t[0]].x < 5) tb.insert(key(lb, t));
    EXPECT_EQ(ta, tb);
    for (std::size_t v = 0; v < a.positions.size(); ++v)
      ASSERT_TRUE(la.positions[la.vertex_of[v]] == lb.positions[lb.vertex_of[v]]) << "vertex " << v;
  }
}

TEST(Clustering, ThinPartsBecomeThickLines) {
  // A tube of radius 0.01 and cell 0.1: its rings collapse to points on the axis, its triangles
  // to edges along it, each as thick as the tube: D_A + D_B = 2 r.
  const float r = 0.01f;
  const TriangleMesh m = tube(r, 1.0f, 12, 50);
  const LodMesh lod = cluster_mesh(m, grade_vertices(m), cells(0.1f));
  EXPECT_EQ(lod.triangles.size(), 0u);
  ASSERT_GE(lod.edges.size(), 5u);
  ASSERT_EQ(lod.thickness.size(), lod.edges.size());
  for (float t : lod.thickness) {
    EXPECT_GT(t, 1.5f * r);
    EXPECT_LT(t, 2.2f * r);
  }
  // Elimination: no degenerate or repeated edges, no edge that is a triangle's side.
  std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
  for (const auto& e : lod.edges) {
    EXPECT_NE(e[0], e[1]);
    EXPECT_TRUE(seen.insert({std::min(e[0], e[1]), std::max(e[0], e[1])}).second);
  }
}

TEST(Clustering, OutputHasNoDegenerateOrDuplicateTriangles) {
  const TriangleMesh m = generate_mesh("cube", 12);
  const VertexGrading g = grade_vertices(m);
  std::size_t last = m.triangles.size() + 1;
  for (float c : {0.4f, 0.9f, 1.5f}) {  // grid spacing 1/6: every size merges
    for (bool uniform : {false, true}) {
      ClusterOptions o = cells(c);
      o.uniform = uniform;
      const LodMesh lod = cluster_mesh(m, g, o);
      std::set<std::array<std::uint32_t, 3>> seen;
      for (Triangle t : lod.triangles) {
        EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
        std::sort(t.begin(), t.end());
        EXPECT_TRUE(seen.insert(t).second);
      }
      for (std::uint32_t p : lod.points)
        for (const Triangle& t : lod.triangles) EXPECT_TRUE(std::find(t.begin(), t.end(), p) == t.end());
      if (!uniform) {
        EXPECT_LT(lod.triangles.size(), last) << "cell " << c;
        last = lod.triangles.size();
      }
    }
  }
}

TEST(Clustering, DeterministicBytes) {
  const TriangleMesh m = generate_mesh("sphere", 16);
  const VertexGrading g = grade_vertices(m);
  EXPECT_EQ(encode_cluster_glb(cluster_mesh(m, g, cells(0.2f))), encode_cluster_glb(cluster_mesh(m, g, cells(0.2f))));
}

TEST(Clustering, DracoStreamDecodesToTheLod) {
  // Every decoded triangle is one of the LOD's, to the 14-bit position quantisation; none lost.
  const TriangleMesh m = generate_mesh("sphere", 16);
  const LodMesh lod = cluster_mesh(m, grade_vertices(m), cells(0.2f));
  DracoInput in;
  for (const Triangle& t : lod.triangles)
    for (std::uint32_t v : t) in.positions.insert(in.positions.end(), {lod.positions[v].x, lod.positions[v].y, lod.positions[v].z});
  const DracoOutput out = draco_compress(in);
  EXPECT_EQ(out.indices, lod.triangles.size() * 3);
  EXPECT_LE(out.vertices, lod.positions.size());
  EXPECT_LT(out.bytes.size(), in.positions.size() * sizeof(float) / 4);  // > 4x smaller than raw floats
  std::vector<float> decoded;
  std::vector<std::uint32_t> corners;
  draco_decode(out.bytes, decoded, corners);
  EXPECT_EQ(corners.size(), lod.triangles.size() * 3);
  const float tol = 2.0f / (1 << 14) * 2;  // the sphere spans 2: one quantisation step, twice
  double worst = 0;
  for (std::size_t i = 0; i + 2 < decoded.size(); i += 3) {
    double best = INFINITY;
    for (Vec3f q : lod.positions) best = std::min(best, double(length(q - Vec3f{decoded[i], decoded[i + 1], decoded[i + 2]})));
    worst = std::max(worst, best);
  }
  EXPECT_LT(worst, tol);
  EXPECT_EQ(draco_compress(in).bytes, out.bytes);  // deterministic
}

TEST(Clustering, ChoosesTheLargestCellWithinXPixels) {
  // R = 2 D tan(15 deg) / 500 = 0.001072 D; X R = 0.00536 D.
  const std::vector<float> c{0.01f, 0.02f, 0.04f, 0.08f};
  EXPECT_EQ(choose_lod(c, 1.0, 30, 500), 0u);   // X R = 0.0054: only 0.01 is too big -> the smallest
  EXPECT_EQ(choose_lod(c, 4.0, 30, 500), 1u);   // X R = 0.021
  EXPECT_EQ(choose_lod(c, 20.0, 30, 500), 3u);  // X R = 0.107
}

// The CGAL meshes: triangle / edge / point counts per cell size (printed), falling as cells grow.
TEST(ClusteringModels, CountsOnCgalMeshes) {
  const char* env = std::getenv("QF_MODELS");
  const std::string dir = env ? env : std::string(std::getenv("HOME") ? std::getenv("HOME") : "") + "/.cache/quasiflat/models";
  if (!std::filesystem::exists(dir + "/bunny00.off")) GTEST_SKIP() << "models not fetched (scripts/fetch-models.sh)";
  for (const char* name : {"bunny00.off", "elephant.off", "fandisk.off", "ChineseDragon-10kv.off"}) {
    const TriangleMesh m = read_model(dir + "/" + name).mesh;
    const VertexGrading g = grade_vertices(m);
    std::size_t last = m.triangles.size() + 1;
    for (float f : {128.f, 64.f, 32.f, 16.f, 8.f}) {
      const LodMesh lod = cluster_mesh(m, g, cells(m.bounds().diagonal() / f));
      std::printf("%-24s cell diag/%-4.0f %7zu triangles %5zu thick edges %4zu points\n", name, f, lod.triangles.size(),
                  lod.edges.size(), lod.points.size());
      EXPECT_LT(lod.triangles.size(), last) << name;
      last = lod.triangles.size();
    }
  }
}

}  // namespace
}  // namespace qf
