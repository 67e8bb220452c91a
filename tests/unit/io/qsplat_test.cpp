// QSplat reader and writer against the test vectors written by the original qsplat_make
// (tests/data/qsplat) and the facts of the QSplat 1.0 format specification.
#include <gtest/gtest.h>

#include <cmath>

#include "core/file_io.h"
#include "io/model_io.h"
#include "io/qsplat_codec.h"
#include "shapes/shapes.h"
#include "test_util.h"

namespace qf {
namespace {

std::string vector_path(const std::string& name) { return test::qsplat_dir() + "/" + name; }

float angle_deg(Vec3f a, Vec3f b) {
  return std::acos(std::clamp(dot(normalized(a), normalized(b)), -1.0f, 1.0f)) * 180.0f / 3.14159265f;
}

// Area-weighted vertex normals, as qsplat_make computes them (§7.1).
std::vector<Vec3f> vertex_normals(const TriangleMesh& m) {
  std::vector<Vec3f> n(m.positions.size());
  for (const Triangle& t : m.triangles) {
    const Vec3f c = cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    for (std::uint32_t i : t) n[i] = n[i] + c;
  }
  for (Vec3f& v : n) v = normalized(v);
  return n;
}

TEST(QSplatTables, SphereTableMatchesSpec) {
  const auto& t = qsplat::sphere_table();
  // §3.2: entries per size s = 1..13 and the first and last entries.
  const int per_size[13] = {1617, 1648, 1331, 1000, 729, 512, 343, 216, 125, 64, 27, 8, 1};
  int index = 0;
  for (int s = 1; s <= 13; ++s) {
    for (int k = 0; k < per_size[s - 1]; ++k) EXPECT_FLOAT_EQ(t[index + k].r, s / 13.0f) << "entry " << index + k;
    index += per_size[s - 1];
  }
  EXPECT_EQ(index, qsplat::kSphereEntries);
  EXPECT_FLOAT_EQ(t[0].x, -12 / 13.0f);
  EXPECT_FLOAT_EQ(t[0].y, -8 / 13.0f);
  EXPECT_FLOAT_EQ(t[0].z, -2 / 13.0f);
  EXPECT_FLOAT_EQ(t[7620].x, 0);
  EXPECT_FLOAT_EQ(t[7620].r, 1);
}

TEST(QSplatTables, NormalTableMatchesSpecExamples) {
  const auto& n = qsplat::normal_table();
  // §8.1: N = 14897 (A=5, U=26, V=25) -> (0.01511, -0.01510, -0.99977); N = 14878 -> (0.01511, -0.66818, -0.74385).
  EXPECT_NEAR(n[14897].x, 0.01511f, 1e-5f);
  EXPECT_NEAR(n[14897].y, -0.01510f, 1e-5f);
  EXPECT_NEAR(n[14897].z, -0.99977f, 1e-5f);
  EXPECT_NEAR(n[14878].y, -0.66818f, 1e-5f);
  EXPECT_NEAR(n[14878].z, -0.74385f, 1e-5f);
  for (const Vec3f& v : n) EXPECT_NEAR(length(v), 1.0f, 1e-5f);  // clamped cells are never NaN
}

TEST(QSplatTables, EncodersInvertDecoders) {
  const auto& n = qsplat::normal_table();
  // Every normal the writer can produce (a cell whose face axis is the dominant component)
  // encodes back to its own index.
  int checked = 0;
  for (int i = 0; i < qsplat::kNormalEntries; ++i) {
    const Vec3f v = n[i];
    const float dom = std::fabs(v[i / 2704 == 0 || i / 2704 == 1 ? 0 : (i / 2704 < 4 ? 1 : 2)]);
    if (dom <= std::fabs(v.x) - 1e-6f || dom <= std::fabs(v.y) - 1e-6f || dom <= std::fabs(v.z) - 1e-6f) continue;
    if (dom < std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)})) continue;
    EXPECT_EQ(qsplat::encode_normal(v), i);
    ++checked;
  }
  EXPECT_GT(checked, 6 * 1400);
  for (int c = 0; c < 65536; c += 7) {
    const auto v = static_cast<std::uint16_t>(c);
    EXPECT_EQ(qsplat::encode_color(qsplat::decode_color(v)), v);
  }
  EXPECT_EQ(qsplat::encode_cone(0), 0);
  EXPECT_EQ(qsplat::encode_cone(0.2f), 1);   // sin 0.2 = 0.199 -> floor(4 sqrt) = 1
  EXPECT_EQ(qsplat::encode_cone(2.0f), 3);   // wider than 1.5 rad: "do not cull"
}

TEST(QSplatRead, PyramidWorkedExample) {
  ReadReport report;
  const PointSet p = read_qsplat(vector_path("pyr.qs"), {}, &report);
  ASSERT_EQ(p.size(), 5u);
  EXPECT_EQ(report.fragments, 1u);
  EXPECT_FALSE(p.has_colors());
  // §8.1, depth first: the four leaves under the root group's first record, then the apex.
  const Vec3f expect[5] = {{0.001625f, 0.001625f, -0.043682f}, {0.998375f, 0.001625f, -0.043682f},
                           {0.998375f, 0.998375f, -0.043682f}, {0.001625f, 0.998375f, -0.043682f},
                           {0.352753f, 0.352753f, 0.941742f}};
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.positions[i][k], expect[i][k], 2e-6f) << "leaf " << i << " axis " << k;
  EXPECT_NEAR(p.radii[4], 0.883483f, 2e-6f);
  EXPECT_NEAR(p.radii[0], 0.872157f, 2e-6f);
  EXPECT_NEAR(p.normals[4].z, 0.99977f, 1e-5f);
  EXPECT_NEAR(p.normals[0].x, -0.58408f, 1e-5f);
}

struct Vector {
  const char* qs;
  const char* ply;
  std::size_t leaves;
};

void PrintTo(const Vector& v, std::ostream* os) { *os << v.qs; }

class QSplatVectors : public ::testing::TestWithParam<Vector> {};

// Every leaf is one source vertex: within the quantisation error of its position, with its
// colour after RGB565 rounding, and its normal within the 14-bit table's error. Near the poles of
// the UV spheres vertices are closer together than that error, so the nearest vertex is not always
// the right one: instead every (leaf, vertex) pair meeting all three conditions is a candidate,
// and a greedy matching by distance must pair every leaf with its own vertex.
TEST_P(QSplatVectors, LeavesMatchSourceVertices) {
  const Vector v = GetParam();
  const PointSet p = read_qsplat(vector_path(v.qs));
  const Model src = read_model(vector_path(v.ply));
  ASSERT_TRUE(src.is_mesh);
  ASSERT_EQ(p.size(), v.leaves);
  ASSERT_EQ(src.mesh.positions.size(), v.leaves);  // qsplat_make keeps every used vertex
  ASSERT_EQ(p.has_colors(), !src.mesh.colors.empty());
  const std::vector<Vec3f> normals = vertex_normals(src.mesh);
  struct Pair {
    float d;
    std::size_t leaf, vertex;
    bool operator<(const Pair& o) const { return std::tie(d, leaf, vertex) < std::tie(o.d, o.leaf, o.vertex); }
  };
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < v.leaves; ++j) {
      const float d = length(p.positions[i] - src.mesh.positions[j]);
      // §3.4: decoded centres are at most 0.57x the original radius off, and decoded radii >= original.
      if (d > 0.6f * p.radii[i]) continue;
      // §4.3: normals within about 3 degrees, dither included.
      if (angle_deg(p.normals[i], normals[j]) > 4.0f) continue;
      if (p.has_colors() && !(p.colors[i] == qsplat::decode_color(qsplat::encode_color(src.mesh.colors[j])))) continue;
      pairs.push_back({d, i, j});
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> leaf_done(p.size(), 0), vertex_done(v.leaves, 0);
  std::size_t matched = 0;
  for (const Pair& q : pairs)
    if (!leaf_done[q.leaf] && !vertex_done[q.vertex]) leaf_done[q.leaf] = vertex_done[q.vertex] = 1, ++matched;
  EXPECT_EQ(matched, v.leaves);
}

INSTANTIATE_TEST_SUITE_P(Original, QSplatVectors,
                         ::testing::Values(Vector{"tet.qs", "tet.ply", 4}, Vector{"pyr.qs", "pyr.ply", 5},
                                           Vector{"sphere_nocol.qs", "sphere_nocol.ply", 2498},
                                           Vector{"sphere_col.qs", "sphere_col.ply", 2498}),
                         [](const ::testing::TestParamInfo<Vector>& param_info) {
                           std::string name = param_info.param.qs;
                           return name.substr(0, name.find('.'));
                         });

TEST(QSplatRead, CommentFragment) {
  const PointSet p = read_qsplat(vector_path("sphere_col.qs"));
  ASSERT_EQ(p.comments.size(), 1u);
  EXPECT_EQ(p.comments[0], "hello qsplat test");
  EXPECT_EQ(p.size(), 2498u);
  EXPECT_TRUE(p.has_colors());
}

TEST(QSplatRead, MultiFragmentIsConcatenation) {
  // multi.qs is sphere_col.qs (a comment and a data fragment), pyr.qs and tet.qs catted together
  // (23624 + 68 + 56 = 23748 bytes; the original notes mentioned only the last two).
  ReadReport report;
  const PointSet multi = read_qsplat(vector_path("multi.qs"), {}, &report);
  const PointSet sphere = read_qsplat(vector_path("sphere_col.qs"));
  const PointSet pyr = read_qsplat(vector_path("pyr.qs"));
  const PointSet tet = read_qsplat(vector_path("tet.qs"));
  EXPECT_EQ(report.fragments, 3u);
  ASSERT_EQ(multi.size(), 2498u + 5u + 4u);
  EXPECT_EQ(multi.comments, sphere.comments);
  for (std::size_t i = 0; i < 2498; ++i) EXPECT_TRUE(multi.positions[i] == sphere.positions[i]);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_TRUE(multi.positions[2498 + i] == pyr.positions[i]);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_TRUE(multi.positions[2503 + i] == tet.positions[i]);
  // pyr and tet have no colour: their leaves are white next to the sphere's colours.
  EXPECT_TRUE(multi.colors[2500] == (Rgb8{255, 255, 255}));
}

// Our writer's file decodes to the points it was given, within the format's quantisation;
// returns the largest centre offset in units of the input radius.
float expect_round_trip(const PointSet& in, float max_offset_in_radii) {
  std::vector<std::uint32_t> order;
  const std::vector<std::uint8_t> bytes = encode_qsplat(in, &order);
  EXPECT_EQ(bytes.size() % 4, 0u);
  const PointSet out = decode_qsplat(bytes, "round-trip");
  EXPECT_EQ(out.size(), in.size());
  EXPECT_EQ(order.size(), in.size());
  EXPECT_EQ(out.comments, in.comments);
  EXPECT_EQ(out.has_colors(), in.has_colors());
  std::vector<int> used(in.size(), 0);
  float worst = 0;
  for (std::size_t i = 0; i < out.size() && i < order.size(); ++i) {
    const std::uint32_t j = order[i];
    ++used[j];
    const float offset = length(out.positions[i] - in.positions[j]) / in.radii[j];
    worst = std::max(worst, offset);
    EXPECT_LE(offset, max_offset_in_radii) << "leaf " << i;
    EXPECT_GE(out.radii[i], 0.999f * in.radii[j]);
    EXPECT_LE(out.radii[i], 3.0f * in.radii[j]);  // whole 1/13 cells of the parent: coarse for small q
    EXPECT_LT(angle_deg(out.normals[i], in.normals[j]), 2.5f);
    if (in.has_colors()) {
      EXPECT_TRUE(out.colors[i] == qsplat::decode_color(qsplat::encode_color(in.colors[j])));
    }
  }
  for (std::size_t j = 0; j < in.size(); ++j) EXPECT_EQ(used[j], 1) << "input point " << j;
  return worst;
}

TEST(QSplatWrite, DecodedOriginalRoundTrips) {
  const PointSet decoded = read_qsplat(vector_path("sphere_col.qs"));
  expect_round_trip(decoded, 0.6f);
  // Decoded colours are 565 values and come back exactly. Decoded normals are table values and
  // come back exactly too, except where the original's random dither stored a normal on a cube
  // face that is not its dominant axis (77 of 2498 here); those move to the canonical face's cell.
  std::vector<std::uint32_t> order;
  const PointSet again = decode_qsplat(encode_qsplat(decoded, &order), "again");
  std::size_t exact = 0;
  for (std::size_t i = 0; i < again.size(); ++i) {
    EXPECT_TRUE(again.colors[i] == decoded.colors[order[i]]);
    exact += again.normals[i] == decoded.normals[order[i]];
  }
  EXPECT_GE(exact, again.size() * 95 / 100);
}

TEST(QSplatWrite, GeneratedShapesRoundTrip) {
  for (const char* shape : {"octahedron", "torus", "crease"}) {
    SCOPED_TRACE(shape);
    ShapeOptions o;
    o.points = 3000;
    expect_round_trip(generate_shape(shape, o), 0.6f);
  }
}

TEST(QSplatWrite, TinyAndDegenerateSets) {
  // 1 to 5 points (the root-has-no-grandchildren cases of §2.4), and many coincident points.
  for (std::size_t n = 1; n <= 5; ++n) {
    PointSet p;
    for (std::size_t i = 0; i < n; ++i) {
      p.positions.push_back({float(i), float(i * i), 0.5f});
      p.normals.push_back({0, 0, 1});
      p.radii.push_back(0.5f);
    }
    SCOPED_TRACE(n);
    if (n == 1) {
      const PointSet out = decode_qsplat(encode_qsplat(p), "one");
      ASSERT_EQ(out.size(), 1u);
      continue;
    }
    // Points 10 radii apart hang straight under a root 20 radii wide: a 1/13 cell of it is
    // ~1.5 radii, so the offsets are larger than in a dense set (the format's limit, not ours).
    expect_round_trip(p, 2.0f);
  }
  PointSet same;
  for (int i = 0; i < 50; ++i) {
    same.positions.push_back({1, 2, 3});
    same.normals.push_back({0, 1, 0});
    same.radii.push_back(0.1f);
  }
  const PointSet out = decode_qsplat(encode_qsplat(same), "coincident");
  ASSERT_EQ(out.size(), 50u);
  for (const Vec3f& q : out.positions) EXPECT_LE(length(q - Vec3f{1, 2, 3}), 0.1f);
}

TEST(QSplatWrite, WriterIsDeterministic) {
  const PointSet p = generate_shape("sphere", {2000, 7});
  EXPECT_EQ(encode_qsplat(p), encode_qsplat(p));
}

}  // namespace
}  // namespace qf
