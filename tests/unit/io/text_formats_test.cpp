// OFF, OBJ, XYZ and PWN readers, the XYZ writer, ASCII PLY values, and the in-memory entry points.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>

#include "core/error.h"
#include "io/model_io.h"
#include "pipeline/asset.h"
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

// ReadOptions::outlier_factor: the bake's loader (load_point_set) drops a stray far from a
// sampled square with every attribute of the other points kept in order; the format reader
// itself does not, nor does the loader at 0 (the readers' default).
TEST(XyzRead, OutliersAreDroppedByTheBakesLoaderOnlyWhenAsked) {
  test::TempDir dir;
  std::string text;
  for (int x = 0; x < 10; ++x)
    for (int y = 0; y < 10; ++y) text += std::to_string(x) + " " + std::to_string(y) + " 0 0 0 1\n";
  text += "5 5 100 0 1 0\n4 4 0 1 0 0\n";  // a stray, then a point of the square
  const std::string path = dir.write("s.pwn", text);
  ReadOptions o;
  ReadReport kept;
  EXPECT_EQ(load_point_set(path, o, SampleOptions{}, "bake", kept).size(), 102u);
  EXPECT_EQ(kept.dropped_outliers, 0u);
  o.outlier_factor = 10;
  EXPECT_EQ(read_model(path, o).points.size(), 102u);
  ReadReport report;
  const PointSet a = load_point_set(path, o, SampleOptions{}, "bake", report);
  EXPECT_EQ(report.dropped_outliers, 1u);
  ASSERT_EQ(a.size(), 101u);
  EXPECT_FLOAT_EQ(a.positions[100].x, 4.0f);
  EXPECT_FLOAT_EQ(a.normals[100].x, 1.0f);  // the last point's normal moved with it
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

// The error an input raises, read from memory (decode_model) and from a file (read_model): the
// same code and message either way.
InputError error_of(const std::string& name, const std::string& bytes) {
  test::TempDir dir;
  const std::string f = dir.write(name, bytes);
  std::string code_from_file;
  try {
    read_model(f);
  } catch (const InputError& e) {
    code_from_file = e.code();
  }
  try {
    decode_model(ByteView(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), f);
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), code_from_file);
    return e;
  }
  ADD_FAILURE() << "accepted " << name;
  return InputError("none", f, "", "");
}

TEST(EmptyTextFiles, AreErrorsNotEmptyModels) {
  // An empty file has no data pointer; each reader says "empty" instead of searching it.
  EXPECT_EQ(error_of("a.off", "").code(), "off.empty");
  EXPECT_EQ(error_of("a.obj", "").code(), "obj.empty");
  EXPECT_EQ(error_of("a.xyz", "").code(), "xyz.empty");
  EXPECT_EQ(error_of("a.pwn", "").code(), "xyz.empty");
  EXPECT_EQ(error_of("b.obj", "# no vertices\ng group\n").code(), "obj.no_vertices");
  EXPECT_EQ(error_of("b.xyz", "# no points\n\n").code(), "xyz.no_points");
  EXPECT_NE(std::string(error_of("a.obj", "").what()).find("empty"), std::string::npos);
}

const char* kAsciiColorHead =
    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";

TEST(PlyAsciiValues, AreCheckedAgainstTheirDeclaredType) {
  const InputError big = error_of("a.ply", std::string(kAsciiColorHead) + "0 0 0 300 0 0\n");
  EXPECT_EQ(big.code(), "ply.body.out_of_range");
  EXPECT_EQ(big.where(), "line 11");
  EXPECT_NE(std::string(big.what()).find("300"), std::string::npos) << big.what();
  EXPECT_NE(std::string(big.what()).find("uchar (0..255)"), std::string::npos) << big.what();
  EXPECT_EQ(error_of("a.ply", std::string(kAsciiColorHead) + "0 0 0 -1 0 0\n").code(), "ply.body.out_of_range");
  // The limits themselves read.
  test::TempDir dir;
  const Model m = read_model(dir.write("ok.ply", std::string(kAsciiColorHead) + "0 0 0 255 0 128\n"));
  ASSERT_EQ(m.points.colors.size(), 1u);
  EXPECT_TRUE(m.points.colors[0] == (Rgb8{255, 0, 128}));
}

TEST(PlyAsciiValues, AFaceIndexBeyondItsTypeGivesTheRealValue) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  const InputError e = error_of("f.ply", head + "3 0 1 9223372036854775807\n");
  EXPECT_EQ(e.code(), "ply.body.out_of_range");
  EXPECT_NE(std::string(e.what()).find("9223372036854775807"), std::string::npos) << e.what();
  EXPECT_EQ(std::string(e.what()).find("-9223372036854775808"), std::string::npos) << e.what();
  // Within int but past the vertices: the index message names the real value too.
  const InputError r = error_of("g.ply", head + "3 0 1 2147483647\n");
  EXPECT_EQ(r.code(), "ply.body.face_index");
  EXPECT_NE(std::string(r.what()).find("2147483647"), std::string::npos) << r.what();
}

TEST(PlyAscii, ElementsWithoutPropertiesAreSkippedAtOnce) {
  // 2^63-1 records of nothing: read at once (it used to loop over the count), as in binary files.
  const std::string body_ascii =
      "ply\nformat ascii 1.0\nelement pad 9223372036854775807\nelement vertex 2\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n0 0 0\n1 2 3\n";
  std::string body_binary = body_ascii.substr(0, body_ascii.find("end_header\n") + 11);
  body_binary.replace(body_binary.find("ascii"), 5, "binary_little_endian");
  const float xyz[6] = {0, 0, 0, 1, 2, 3};
  body_binary.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  test::TempDir dir;
  const auto start = std::chrono::steady_clock::now();
  for (const std::string& bytes : {body_ascii, body_binary}) {
    const Model m = read_model(dir.write("pad.ply", bytes));
    ASSERT_EQ(m.points.size(), 2u);
    EXPECT_FLOAT_EQ(m.points.positions[1].z, 3.0f);
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(DecodeModel, ReadsFromMemoryLikeTheFileReaders) {
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const Model m = decode_model(ByteView(reinterpret_cast<const std::uint8_t*>(off.data()), off.size()), "mem.off");
  ASSERT_TRUE(m.is_mesh);
  EXPECT_EQ(m.mesh.triangles.size(), 1u);
  EXPECT_THROW(decode_model(ByteView(), "mem.stl"), UsageError);
}

}  // namespace
}  // namespace qf
