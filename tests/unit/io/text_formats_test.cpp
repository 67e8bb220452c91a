// OFF, OBJ, XYZ and PWN readers, and the XYZ writer.
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/model_io.h"
#include "test_util.h"

namespace qf {
namespace {

TEST(OffRead, PlainWithCommentsAndPolygons) {
  test::TempDir dir;
  const std::string f = dir.write("a.off",
                                  "OFF # a comment\n# another\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                  "4 0 1 2 3 255 0 0\n3 0 2 3\n");
  ReadReport report;
  const TriangleMesh m = read_off(f, {}, &report);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(report.polygons_triangulated, 1u);
  EXPECT_TRUE(m.colors.empty());
}

TEST(OffRead, ColorAndNormalVariants) {
  test::TempDir dir;
  const TriangleMesh c = read_off(dir.write("c.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 128 0 255\n0 1 0 0 0 64 255\n3 0 1 2\n"));
  ASSERT_EQ(c.colors.size(), 3u);
  EXPECT_TRUE(c.colors[1] == (Rgb8{0, 128, 0}));
  const TriangleMesh cf = read_off(dir.write("cf.off", "COFF\n3 1 0\n0 0 0 1.0 0.5 0.0 1.0\n1 0 0 0 0 0 1\n0 1 0 0 0 0 1\n3 0 1 2\n"));
  EXPECT_TRUE(cf.colors[0] == (Rgb8{255, 128, 0}));
  const TriangleMesh n = read_off(dir.write("n.off", "NOFF 3 1 0\n0 0 0 0 0 2\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"));
  ASSERT_EQ(n.normals.size(), 3u);
  EXPECT_FLOAT_EQ(n.normals[0].z, 1.0f);
}

TEST(ObjRead, EveryIndexForm) {
  test::TempDir dir;
  const std::string f = dir.write("a.obj",
                                  "# cube corner\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                  "vt 0 0\nvn 0 0 1\ng group\ns off\nusemtl m\n"
                                  "f 1/1/1 2/1/1 3/1/1\nf 1//1 3//1 4//1\nf -4 -2 -1\nf 1/1 2/1 3/1 4/1\nl 1 2\n");
  ReadReport report;
  const TriangleMesh m = read_obj(f, {}, &report);
  EXPECT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.triangles.size(), 5u);
  EXPECT_EQ(m.triangles[2], (Triangle{0, 2, 3}));  // negative indices count back from the last vertex
  EXPECT_EQ(report.polygons_triangulated, 1u);
  ASSERT_EQ(m.normals.size(), 4u);
  EXPECT_FLOAT_EQ(m.normals[3].z, 1.0f);
  EXPECT_TRUE(m.colors.empty());
}

TEST(ObjRead, VertexColors) {
  test::TempDir dir;
  const TriangleMesh m = read_obj(dir.write("c.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n"));
  ASSERT_EQ(m.colors.size(), 3u);
  EXPECT_TRUE(m.colors[2] == (Rgb8{0, 0, 128}));
}

TEST(XyzRead, PointsWithAndWithoutNormals) {
  test::TempDir dir;
  const PointSet a = read_xyz(dir.write("a.xyz", "# points\n0 0 0\n1 2 3\r\n\n4 5 6"), false);
  EXPECT_EQ(a.size(), 3u);
  EXPECT_FALSE(a.has_normals());
  EXPECT_FLOAT_EQ(a.positions[2].z, 6.0f);
  const PointSet b = read_xyz(dir.write("b.pwn", "0 0 0 0 0 1\n1 0 0 0 3 0\n"), true);
  ASSERT_TRUE(b.has_normals());
  EXPECT_FLOAT_EQ(b.normals[1].y, 1.0f);
}

TEST(XyzWrite, RoundTripIsExact) {
  test::TempDir dir;
  PointSet p;
  p.positions = {{0.1f, -2.5e-7f, 3e8f}, {-0.0f, 1.0f / 3.0f, 7.0f}};
  p.normals = {{0, 0, 1}, {0.6f, 0.8f, 0}};
  write_point_set(dir.path("p.pwn"), p);
  const PointSet q = read_xyz(dir.path("p.pwn"), true);
  ASSERT_EQ(q.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_TRUE(q.positions[i] == p.positions[i]);
  EXPECT_THROW(write_point_set(dir.path("x.pwn"), PointSet{{{0, 0, 0}}, {}, {}, {}, {}, {}}), InputError);
  EXPECT_THROW(write_point_set(dir.path("x.stl"), p), UsageError);
}

}  // namespace
}  // namespace qf
