// PLY reader (every encoding, property type and layout quirk) and binary writer.
#include <gtest/gtest.h>

#include <cstring>
#include <optional>

#include "core/error.h"
#include "io/model_io.h"
#include "shapes/shapes.h"
#include "test_util.h"

namespace qf {
namespace {

template <class T>
std::string raw(T v, bool big_endian = false) {
  std::string s(sizeof v, '\0');
  std::memcpy(s.data(), &v, sizeof v);
  if (big_endian) std::reverse(s.begin(), s.end());
  return s;
}

TEST(PlyRead, AsciiWithEverySpelling) {
  test::TempDir dir;
  // diffuse_* colours, a "scale" radius, unknown scalar and list properties, an unknown element
  // before the vertices, CRLF line endings and comments.
  const std::string f = dir.write("a.ply",
                                  "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info x\r\n"
                                  "element material 1\r\nproperty uchar ambient\r\nproperty list uchar float coeffs\r\n"
                                  "element vertex 2\r\nproperty double x\r\nproperty float y\r\nproperty short z\r\n"
                                  "property float confidence\r\nproperty list uint8 int32 junk\r\n"
                                  "property float nx\r\nproperty float ny\r\nproperty float nz\r\n"
                                  "property uchar diffuse_red\r\nproperty uchar diffuse_green\r\nproperty uchar diffuse_blue\r\n"
                                  "property float scale\r\nend_header\r\n"
                                  "7 3 0.5 0.25 0.125\r\n"
                                  "1.5 -2 3 0.9 2 5 6 0 0 2 255 128 0 0.25\r\n"
                                  "-1e-3 4.5e2 -7 0.1 0 0 1 0 10 20 30 0.5\r\n");
  ReadReport report;
  const Model m = read_ply(f, {}, &report);
  ASSERT_FALSE(m.is_mesh);
  EXPECT_EQ(report.format, "ply (ascii)");
  const PointSet& p = m.points;
  ASSERT_EQ(p.size(), 2u);
  EXPECT_FLOAT_EQ(p.positions[0].x, 1.5f);
  EXPECT_FLOAT_EQ(p.positions[0].y, -2.0f);
  EXPECT_FLOAT_EQ(p.positions[0].z, 3.0f);
  EXPECT_FLOAT_EQ(p.positions[1].x, -1e-3f);
  EXPECT_FLOAT_EQ(p.positions[1].y, 450.0f);
  ASSERT_TRUE(p.has_normals());
  EXPECT_FLOAT_EQ(p.normals[0].z, 1.0f);  // (0,0,2) normalised
  ASSERT_TRUE(p.has_colors());
  EXPECT_TRUE(p.colors[0] == (Rgb8{255, 128, 0}));
  EXPECT_TRUE(p.colors[1] == (Rgb8{10, 20, 30}));
  ASSERT_TRUE(p.has_radii());
  EXPECT_FLOAT_EQ(p.radii[1], 0.5f);
  ASSERT_EQ(p.comments.size(), 1u);
  EXPECT_EQ(p.comments[0], "made by hand");
}

TEST(PlyRead, BinaryBigAndLittleEndianAnyTypes) {
  for (bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    test::TempDir dir;
    std::string body;
    // vertex: int x, ushort y, double z, float red/green/blue (0..1), uchar flag (unknown)
    for (int i = 0; i < 3; ++i) {
      body += raw<std::int32_t>(-i, big) + raw<std::uint16_t>(static_cast<std::uint16_t>(1000 + i), big) +
              raw<double>(0.25 * i, big);
      body += raw<float>(1.0f, big) + raw<float>(0.5f, big) + raw<float>(0.0f, big) + raw<std::uint8_t>(9);
    }
    // an unknown element with a list between the vertices and the end
    body += raw<std::uint16_t>(3, big) + raw<std::int8_t>(1) + raw<std::int8_t>(2) + raw<std::int8_t>(3);
    const std::string header = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                               " 1.0\nelement vertex 3\nproperty int x\nproperty ushort y\nproperty double z\n"
                               "property float red\nproperty float green\nproperty float blue\nproperty uchar flag\n"
                               "element extra 1\nproperty list ushort char values\nend_header\n";
    const Model m = read_ply(dir.write("b.ply", header + body));
    ASSERT_EQ(m.points.size(), 3u);
    EXPECT_FLOAT_EQ(m.points.positions[2].x, -2.0f);
    EXPECT_FLOAT_EQ(m.points.positions[2].y, 1002.0f);
    EXPECT_FLOAT_EQ(m.points.positions[2].z, 0.5f);
    EXPECT_TRUE(m.points.colors[1] == (Rgb8{255, 128, 0}));
    EXPECT_FALSE(m.points.has_normals());
    EXPECT_FALSE(m.points.has_radii());
  }
}

TEST(PlyRead, FacesMakeAMeshAndPolygonsAreSplit) {
  test::TempDir dir;
  std::string body;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) body += raw(v);
  // a quad (uint8 count, uint32 indices) with a per-face uchar property after the list
  body += raw<std::uint8_t>(4) + raw<std::uint32_t>(0) + raw<std::uint32_t>(1) + raw<std::uint32_t>(2) +
          raw<std::uint32_t>(3) + raw<std::uint8_t>(7);
  body += raw<std::uint8_t>(3) + raw<std::uint32_t>(3) + raw<std::uint32_t>(2) + raw<std::uint32_t>(0) + raw<std::uint8_t>(7);
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar uint vertex_index\nproperty uchar material\nend_header\n";
  ReadReport report;
  const Model m = read_ply(dir.write("m.ply", header + body), {}, &report);
  ASSERT_TRUE(m.is_mesh);
  ASSERT_EQ(m.mesh.triangles.size(), 3u);
  EXPECT_EQ(report.polygons_triangulated, 1u);
  EXPECT_EQ(m.mesh.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(m.mesh.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(m.mesh.triangles[2], (Triangle{3, 2, 0}));
}

TEST(PlyRead, SharedSourceMeshes) {
  // The PLY sources of the QSplat vectors: binary big-endian meshes, diffuse_* colours, comments.
  const Model m = read_model(test::qsplat_dir() + "/sphere_col.ply");
  ASSERT_TRUE(m.is_mesh);
  EXPECT_EQ(m.mesh.positions.size(), 2498u);
  EXPECT_EQ(m.mesh.triangles.size(), 4992u);
  EXPECT_EQ(m.mesh.colors.size(), 2498u);
  EXPECT_EQ(m.mesh.comments, std::vector<std::string>{"hello qsplat test"});
  const Model pyr = read_model(test::qsplat_dir() + "/pyr.ply");
  EXPECT_EQ(pyr.mesh.positions.size(), 5u);
  EXPECT_EQ(pyr.mesh.triangles.size(), 6u);
}

TEST(PlyWrite, RoundTripKeepsEveryAttribute) {
  test::TempDir dir;
  PointSet p = generate_shape("torus", {500, 3});
  p.comments.push_back("second\nline");
  const std::string f = dir.path("t.ply");
  write_ply(f, p);
  const Model m = read_ply(f);
  ASSERT_FALSE(m.is_mesh);
  EXPECT_EQ(m.points.positions.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_TRUE(m.points.positions[i] == p.positions[i]);
    EXPECT_TRUE(m.points.colors[i] == p.colors[i]);
    EXPECT_EQ(m.points.radii[i], p.radii[i]);
    EXPECT_NEAR(m.points.normals[i].x, p.normals[i].x, 1e-7f);
  }
  EXPECT_EQ(m.points.comments, (std::vector<std::string>{p.comments[0], "second", "line"}));
  EXPECT_EQ(dir.files(), std::vector<std::string>{"t.ply"});  // no temporary left behind
}

TEST(PlyWrite, MeshRoundTrip) {
  test::TempDir dir;
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.colors = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  mesh.triangles = {{0, 1, 2}};
  write_ply(dir.path("m.ply"), mesh);
  const Model m = read_ply(dir.path("m.ply"));
  ASSERT_TRUE(m.is_mesh);
  EXPECT_EQ(m.mesh.triangles, mesh.triangles);
  EXPECT_TRUE(m.mesh.colors[2] == (Rgb8{7, 8, 9}));
}

TEST(PlyRead, DropNonFiniteOnRequest) {
  test::TempDir dir;
  const std::string f = dir.write("n.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                  "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                                  "end_header\n0 0 0 1 1 1\nnan 0 0 2 2 2\n1 inf 0 3 3 3\n1 1 1 4 4 4\n");
  EXPECT_THROW(read_ply(f), InputError);
  ReadOptions o;
  o.drop_nonfinite = true;
  ReadReport report;
  const Model m = read_ply(f, o, &report);
  EXPECT_EQ(report.dropped_nonfinite, 2u);
  ASSERT_EQ(m.points.size(), 2u);
  EXPECT_TRUE(m.points.colors[1] == (Rgb8{4, 4, 4}));
}

// The points a stream hands over, its blocks concatenated; `sizes` gets each block's size.
PointSet streamed(const std::string& path, const ReadOptions& o, ReadReport* report, std::size_t block,
                  std::vector<std::size_t>& sizes) {
  PointSet all;
  stream_point_set(path, o, report, block, [&](PointSet& b) {
    sizes.push_back(b.size());
    all.positions.insert(all.positions.end(), b.positions.begin(), b.positions.end());
    all.normals.insert(all.normals.end(), b.normals.begin(), b.normals.end());
    all.colors.insert(all.colors.end(), b.colors.begin(), b.colors.end());
    all.radii.insert(all.radii.end(), b.radii.begin(), b.radii.end());
    all.comments = b.comments;
  });
  return all;
}

TEST(PlyRead, StreamedBlocksAreTheWholeRead) {
  test::TempDir dir;
  PointSet p = generate_shape("sphere", {5000, 3});
  p.radii.assign(p.size(), 0.01f);
  p.colors.assign(p.size(), Rgb8{1, 2, 3});
  p.comments = {"made by a test"};
  write_ply(dir.path("s.ply"), p);
  EXPECT_EQ(streamed_point_count(dir.path("s.ply")), std::optional<std::size_t>(5000));
  const PointSet whole = read_ply(dir.path("s.ply")).points;
  std::vector<std::size_t> sizes;
  ReadReport report;
  const PointSet got = streamed(dir.path("s.ply"), {}, &report, 1200, sizes);
  EXPECT_EQ(sizes, (std::vector<std::size_t>{1200, 1200, 1200, 1200, 200}));
  EXPECT_TRUE(got.positions == whole.positions);
  EXPECT_TRUE(got.normals == whole.normals);
  EXPECT_TRUE(got.radii == whole.radii);
  EXPECT_TRUE(got.colors == whole.colors);
  EXPECT_EQ(got.comments, whole.comments);
  EXPECT_EQ(report.format, "ply (binary_little_endian)");
  // Non-finite points dropped block by block, counted; refused without --drop-nonfinite.
  const std::string f = dir.write("n.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                                  "property float z\nend_header\n0 0 0\nnan 0 0\n1 1 0\n1 inf 0\n1 1 1\n");
  sizes.clear();
  EXPECT_THROW(streamed(f, {}, nullptr, 2, sizes), InputError);
  ReadOptions drop;
  drop.drop_nonfinite = true;
  ReadReport dropped;
  sizes.clear();
  const PointSet finite = streamed(f, drop, &dropped, 2, sizes);
  EXPECT_EQ(dropped.dropped_nonfinite, 2u);
  EXPECT_EQ(sizes, (std::vector<std::size_t>{1, 1, 1}));
  EXPECT_TRUE(finite.positions == (std::vector<Vec3f>{{0, 0, 0}, {1, 1, 0}, {1, 1, 1}}));
  // A mesh does not stream; its count is not offered.
  const std::string mesh = dir.write("m.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                     "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(streamed_point_count(mesh), std::nullopt);
  EXPECT_THROW(streamed(mesh, {}, nullptr, 2, sizes), UsageError);
  EXPECT_EQ(streamed_point_count(dir.write("x.xyz", "0 0 0\n")), std::nullopt);
}

TEST(PlyRead, DropNonFiniteMeshVerticesTakesTheirTriangles) {
  test::TempDir dir;
  const std::string f = dir.write("n.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                  "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                                  "end_header\n0 0 0\nnan 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  ReadOptions o;
  o.drop_nonfinite = true;
  ReadReport report;
  const Model m = read_ply(f, o, &report);
  EXPECT_EQ(report.dropped_nonfinite, 1u);
  EXPECT_EQ(report.dropped_triangles, 1u);
  ASSERT_EQ(m.mesh.triangles.size(), 1u);
  EXPECT_EQ(m.mesh.triangles[0], (Triangle{0, 1, 2}));  // reindexed past the dropped vertex
}

}  // namespace
}  // namespace qf
