// Textured inputs: glTF 2.0 and OBJ + MTL read with their materials, and sampled with their colours
// (tests/data/textured, written by make.py there: a cube with a 4x4 texture of four 2x2 quadrants).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"
#include "io/model_io.h"
#include "sample/sample.h"
#include "test_util.h"

namespace qf {
namespace {

std::string asset(const std::string& name) { return test::test_data_dir() + "/textured/" + name; }

PointSet sampled(const std::string& name) {
  SampleOptions o;
  o.ldi_size = 64;
  return sample_mesh(read_model(asset(name)).mesh, o, name);
}

// The +Z face of the cube (z = 5 in the world) has u = (x - 1) / 2 and v = 1 - (y - 2) / 2; the
// texture's quadrants are red (top left), green (top right), blue (bottom left), white.
struct FacePoint {
  double u, v;
  Rgb8 color;
};
std::vector<FacePoint> top_face(const PointSet& p) {
  std::vector<FacePoint> out;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::fabs(p.positions[i].z - 5) < 1e-4 && p.normals[i].z > 0.99)
      out.push_back({(p.positions[i].x - 1) / 2.0, 1 - (p.positions[i].y - 2) / 2.0, p.colors[i]});
  return out;
}

Rgb8 quadrant(double u, double v) {
  if (v < 0.5) return u < 0.5 ? Rgb8{255, 0, 0} : Rgb8{0, 255, 0};
  return u < 0.5 ? Rgb8{0, 0, 255} : Rgb8{255, 255, 255};
}

TEST(TexturedGltf, NodeTransformsPlaceTheMeshWhereAnEngineDoes) {
  ReadReport report;
  const Model m = read_model(asset("cube.gltf"), {}, &report);
  ASSERT_TRUE(m.is_mesh);
  EXPECT_EQ(report.format, "gltf");
  const Bounds b = m.mesh.bounds();
  // translate (1, 2, 3) after scale 2 of the unit cube
  EXPECT_FLOAT_EQ(b.min.x, 1);
  EXPECT_FLOAT_EQ(b.min.y, 2);
  EXPECT_FLOAT_EQ(b.min.z, 3);
  EXPECT_FLOAT_EQ(b.max.x, 3);
  EXPECT_FLOAT_EQ(b.max.y, 4);
  EXPECT_FLOAT_EQ(b.max.z, 5);
  EXPECT_EQ(m.mesh.triangles.size(), 12u);
  ASSERT_EQ(m.mesh.textures.size(), 1u);
  EXPECT_EQ(m.mesh.textures[0].width, 4);
  EXPECT_EQ(m.mesh.corner_uvs.size(), 12u);
}

// Normals go by the inverse transpose of the node's matrix: a rotation turns them with the
// positions (the adjugate turned them back: 2CylinderEngine's rotated parts lit wrongly), a mirror
// flips them with the winding.
TEST(TexturedGltf, NodeTransformsTurnNormalsAsAnEngineDoes) {
  // The triangle (0,0,0) (1,0,0) (0,1,0) with NORMAL (0,0,1) at each corner.
  const auto normal_under = [](const std::string& node) {
    test::TempDir dir;
    const std::string path = dir.write("n.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)" + node + R"(],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":2}]}],
  "buffers":[{"byteLength":78,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAABAAIA"}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":36},{"buffer":0,"byteOffset":72,"byteLength":6}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
               {"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"},
               {"bufferView":2,"componentType":5123,"count":3,"type":"SCALAR"}]})");
    const Model m = read_model(path);
    EXPECT_EQ(m.mesh.normals.size(), 3u);
    return m.mesh.normals.empty() ? Vec3f{} : m.mesh.normals[0];
  };
  // 90 degrees about x: y goes to z, z to -y.
  const Vec3f turned = normal_under(R"({"mesh":0,"rotation":[0.70710678,0,0,0.70710678]})");
  EXPECT_NEAR(turned.x, 0, 1e-6);
  EXPECT_NEAR(turned.y, -1, 1e-6);
  EXPECT_NEAR(turned.z, 0, 1e-6);
  // Mirrored in z, scaled in x: the normal is -z.
  const Vec3f mirrored = normal_under(R"({"mesh":0,"scale":[3,1,-1]})");
  EXPECT_NEAR(mirrored.x, 0, 1e-6);
  EXPECT_NEAR(mirrored.y, 0, 1e-6);
  EXPECT_NEAR(mirrored.z, -1, 1e-6);
}

TEST(TexturedGltf, SampledPointsCarryTheTexelsAtTheirUvs) {
  const std::vector<FacePoint> face = top_face(sampled("cube.gltf"));
  ASSERT_GT(face.size(), 1000u);
  std::size_t checked = 0;
  for (const FacePoint& p : face) {
    // Away from the quadrant borders (and the edges, where the repeating sampler wraps around)
    // the bilinear lookup meets only one quadrant's texels.
    if (std::fabs(p.u - 0.5) < 0.13 || std::fabs(p.v - 0.5) < 0.13 || std::fabs(p.u - 0.5) > 0.37 || std::fabs(p.v - 0.5) > 0.37) continue;
    const Rgb8 want = quadrant(p.u, p.v);
    ASSERT_LE(std::abs(p.color.r - want.r), 2) << p.u << " " << p.v;
    ASSERT_LE(std::abs(p.color.g - want.g), 2) << p.u << " " << p.v;
    ASSERT_LE(std::abs(p.color.b - want.b), 2) << p.u << " " << p.v;
    ++checked;
  }
  EXPECT_GT(checked, 300u);
}

TEST(TexturedGltf, MaskCutOutsGiveNoPoints) {
  // cube_mask: the texture's left half has alpha 0 (cutoff 0.5 falls at u = 0.5).
  const std::vector<FacePoint> face = top_face(sampled("cube_mask.gltf"));
  ASSERT_GT(face.size(), 500u);
  for (const FacePoint& p : face) ASSERT_GT(p.u, 0.49) << "a point where the texture is cut away";
  const std::vector<FacePoint> full = top_face(sampled("cube.gltf"));
  EXPECT_NEAR(static_cast<double>(face.size()) / static_cast<double>(full.size()), 0.5, 0.03);
}

TEST(TexturedObj, MtlGivesTheSameColoursAsTheSameModelInGltf) {
  const PointSet obj = sampled("cube.obj");
  const PointSet gltf = sampled("cube.gltf");
  ASSERT_EQ(obj.size(), gltf.size());
  ASSERT_TRUE(obj.has_colors());
  for (std::size_t i = 0; i < obj.size(); ++i) {
    ASSERT_NEAR(obj.positions[i].x, gltf.positions[i].x, 1e-5);
    ASSERT_LE(std::abs(obj.colors[i].r - gltf.colors[i].r), 1) << i;
    ASSERT_LE(std::abs(obj.colors[i].g - gltf.colors[i].g), 1) << i;
    ASSERT_LE(std::abs(obj.colors[i].b - gltf.colors[i].b), 1) << i;
  }
}

TEST(TexturedObj, UntexturedMeshesStayUncoloured) {
  test::TempDir dir;
  const std::string path = dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nothing\nf 1 2 3\n");
  const Model m = read_model(path);
  EXPECT_FALSE(m.mesh.has_surface_color());
  SampleOptions o;
  o.ldi_size = 16;
  EXPECT_FALSE(sample_mesh(m.mesh, o, path).has_colors());
}

// The files a model reads besides itself, as the batch's keys hash them.
std::vector<std::string> dependency_names(const std::string& path) {
  std::vector<std::string> out;
  for (const InputDependency& d : input_dependencies(path)) out.push_back(d.name);
  return out;
}

TEST(InputDependencies, ListTheExternalFilesTheReadersOpen) {
  // The cube's buffer is a data: URI (inside the file), its image external.
  EXPECT_EQ(dependency_names(asset("cube.gltf")), std::vector<std::string>{"cube.png"});
  ASSERT_EQ(input_dependencies(asset("cube.gltf")).size(), 1u);
  EXPECT_EQ(input_dependencies(asset("cube.gltf"))[0].path, asset("cube.png"));
  EXPECT_EQ(dependency_names(asset("cube.obj")), (std::vector<std::string>{"cube.mtl", "cube.png"}));
  test::TempDir dir;
  // Buffers before images, percent-decoding, each once, missing files listed; an MTL in another
  // folder names its images relative to itself, options before the image name skipped.
  const std::string gltf = dir.write("a.gltf", R"({"asset":{"version":"2.0"},"buffers":[{"uri":"my%20data.bin","byteLength":4},
    {"uri":"data:application/octet-stream;base64,AAAA","byteLength":3}],"images":[{"uri":"t.png"},{"uri":"t.png"},{"bufferView":0}]})");
  EXPECT_EQ(dependency_names(gltf), (std::vector<std::string>{"my data.bin", "t.png"}));
  std::filesystem::create_directories(dir.path("mat"));
  dir.write("mat/m.mtl", "newmtl a\nmap_Kd -s 1 1 1 tex\\wood.png\n# map_Kd not.png\n");
  const std::string obj = dir.write("b.obj", "mtllib mat/m.mtl\nmtllib gone.mtl\nv 0 0 0\n");
  EXPECT_EQ(dependency_names(obj), (std::vector<std::string>{"mat/m.mtl", "mat/tex/wood.png", "gone.mtl"}));
  // Formats without external files, and glTF text that does not parse, give none.
  EXPECT_TRUE(input_dependencies(dir.write("c.off", "OFF\n0 0 0\n")).empty());
  EXPECT_TRUE(input_dependencies(dir.write("d.gltf", "{not json")).empty());
}

// A one-triangle glTF in a string: `indices` is the base64 of its three u16 indices, `extra` more
// top-level members.
std::string triangle_gltf(const std::string& indices, const std::string& extra = "", const std::string& nodes = R"("nodes":[{"mesh":0}],)") {
  // Three float positions (0,0,0) (1,0,0) (0,1,0), then three u16 indices: base64 of 42 bytes.
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)" + extra + nodes +
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
  "buffers":[{"byteLength":42,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA)" +
         indices + R"("}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
               {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
}

std::string error_of(const std::string& name, const std::string& text) {
  test::TempDir dir;
  const std::string path = dir.write(name, text);
  try {
    read_model(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MalformedGltf, ErrorsNameTheJsonPathAndWhatWasExpected) {
  // Indices 0 1 2 read; 0 1 12 is out of range.
  EXPECT_EQ(error_of("ok.gltf", triangle_gltf("AAABAAIA") + "\n").find("no error"), 0u);
  const std::string range = error_of("range.gltf", triangle_gltf("AAABAAwA"));
  EXPECT_NE(range.find("meshes[0].primitives[0].indices: index 12 out of range (3 vertices)"), std::string::npos) << range;
  EXPECT_NE(range.find("range.gltf"), std::string::npos);
  const std::string cycle = error_of("cycle.gltf", triangle_gltf("AAABAAIA", "", R"("nodes":[{"children":[1]},{"children":[0],"mesh":0}],)"));
  EXPECT_NE(cycle.find("is its own ancestor"), std::string::npos) << cycle;
  const std::string ext = error_of("ext.gltf", triangle_gltf("AAABAAIA", R"("extensionsRequired":["EXT_unknown"],)"));
  EXPECT_NE(ext.find("requires the extension EXT_unknown"), std::string::npos) << ext;
  const std::string type = error_of("type.gltf", triangle_gltf("AAABAAIA", R"("materials":[{"alphaCutoff":"half"}],)"));
  EXPECT_NE(type.find("materials[0].alphaCutoff: expected a number, found a string"), std::string::npos) << type;
  std::string textured = triangle_gltf(
      "AAABAAIA", R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],"textures":[{"source":0}],"images":[{"uri":"missing.png"}],)");
  textured.replace(textured.find(R"("indices":1})"), 12, R"("indices":1,"material":0})");
  const std::string image = error_of("image.gltf", textured);
  EXPECT_NE(image.find("images[0] (missing.png)"), std::string::npos) << image;
}

// A texture cut short is refused by the image plug-in before OpenImageIO reads it (whose PNG
// reader leaked on it: tests/fuzz/README.md), for glTF and for OBJ + MTL alike.
TEST(MalformedGltf, TruncatedPngTexturesAreRefused) {
  test::TempDir dir;
  std::ifstream in(asset("cube.png"), std::ios::binary);
  const std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(png.size(), 40u);
  dir.write("cut.png", png.substr(0, png.size() - 20));  // IEND and part of IDAT gone
  std::string textured = triangle_gltf(
      "AAABAAIA", R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],"textures":[{"source":0}],"images":[{"uri":"cut.png"}],)");
  textured.replace(textured.find(R"("indices":1})"), 12, R"("indices":1,"material":0})");
  const std::string gltf = dir.write("cut.gltf", textured);
  try {
    read_model(gltf);
    ADD_FAILURE() << "a truncated PNG read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("images[0] (cut.png): is a truncated PNG file"), std::string::npos) << e.what();
  }
  dir.write("cut.mtl", "newmtl m\nmap_Kd cut.png\n");
  const std::string obj = dir.write("cut.obj", "mtllib cut.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
  try {
    read_model(obj);
    ADD_FAILURE() << "a truncated PNG read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), "mtl.image");
    EXPECT_NE(std::string(e.what()).find("truncated PNG"), std::string::npos) << e.what();
  }
  // The whole file reads.
  dir.write("cut.png", png);
  EXPECT_EQ(read_model(gltf).mesh.textures.size(), 1u);
}

}  // namespace
}  // namespace qf
