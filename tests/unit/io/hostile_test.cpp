// Hostile glTF and OBJ inputs (issue 50): deep JSON, node chains and DAGs, huge counts, images
// whose headers claim more than the memory allows, references leading outside the asset's folder.
// Each must be an InputError with its code, never a crash, an allocation of what the file claims,
// or a read of another file.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_limits.h"
#include "core/parallel_errors.h"
#include "io/model_io.h"
#include "sample/sample.h"
#include "test_util.h"

namespace qf {
namespace {

namespace fs = std::filesystem;

// One triangle: 3 float positions and 3 u16 indices in a 42-byte buffer named by `buffer_uri`
// (a data: URI unless given), `extra` top-level keys and `nodes` as given.
const char* kTriangleData = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIA";
std::string gltf(const std::string& nodes = R"([{"mesh":0}])", const std::string& extra = "", const std::string& buffer_uri = kTriangleData,
                 const std::string& count = "3") {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)" + extra + R"("nodes":)" + nodes +
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
  "buffers":[{"byteLength":42,"uri":")" + buffer_uri + R"("}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":)" + count + R"(,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
               {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
}

// The InputError reading `path` throws ("no error" if none), as "code: message".
std::string error_of(const std::string& path, const ReadOptions& o = {}) {
  try {
    read_model(path, o);
  } catch (const InputError& e) {
    return e.code() + ": " + e.what();
  }
  return "no error";
}

std::string chain(std::size_t n, bool twice) {
  std::string s = "[";
  for (std::size_t i = 0; i + 1 < n; ++i)
    s += R"({"children":[)" + std::to_string(i + 1) + (twice ? "," + std::to_string(i + 1) : "") + "]},";
  return s + R"({"mesh":0}])";
}

// A PNG of nothing but its signature and an IHDR claiming `side` x `side` RGBA texels.
std::string png_header(std::uint32_t side) {
  std::string s("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16);
  for (int k = 0; k < 2; ++k)
    for (int b = 3; b >= 0; --b) s += static_cast<char>((side >> (8 * b)) & 0xFF);
  return s + std::string("\x08\x06\0\0\0\0\0\0\0", 9);
}

std::string textured(const std::string& image_uri, int images) {
  std::string list, textures;
  for (int i = 0; i < images; ++i) {
    list += std::string(i ? "," : "") + R"({"uri":")" + image_uri + R"("})";
    textures += std::string(i ? "," : "") + R"({"source":)" + std::to_string(i) + "}";
  }
  return R"("images":[)" + list + R"(],"textures":[)" + textures + "],";
}

TEST(Hostile, DeepJsonIsRefusedBeforeParsing) {
  test::TempDir dir;
  // 30 KB nested 15,000 deep in extras: tinygltf's recursive parser overflowed the stack on it.
  const std::string deep = R"("extras":)" + std::string(15000, '[') + std::string(15000, ']') + ",";
  const std::string e = error_of(dir.write("deep.gltf", gltf(R"([{"mesh":0}])", deep)));
  EXPECT_EQ(e.rfind("gltf.json_depth: ", 0), 0u) << e;
  EXPECT_NE(e.find("nests 15001 levels deep"), std::string::npos) << e;
  const std::string tricky = R"({"a":"[[[[","b":[[1],{"c":"\"]"}]})";
  EXPECT_EQ(json_nesting_depth(tricky.data(), tricky.size()), 3u);
  // As deep as allowed still reads.
  const std::string fine = R"("extras":)" + std::string(kMaxJsonDepth - 1, '[') + std::string(kMaxJsonDepth - 1, ']') + ",";
  EXPECT_EQ(error_of(dir.write("fine.gltf", gltf(R"([{"mesh":0}])", fine))), "no error");
}

// The one-triangle asset as a .glb, its buffer in the BIN chunk (42 bytes padded to 44); the BIN
// chunk's length and the buffer's byteLength both claim `claimed` bytes.
std::string glb_triangle(std::uint32_t claimed) {
  std::string json = gltf();
  const std::string uri_buffer = std::string(R"("byteLength":42,"uri":")") + kTriangleData + "\"";
  json.replace(json.find(uri_buffer), uri_buffer.size(), "\"byteLength\":" + std::to_string(claimed));
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::string bin(44, '\0');
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[3] = {0, 1, 2};
  std::memcpy(&bin[0], positions, sizeof positions);
  std::memcpy(&bin[36], indices, sizeof indices);
  const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const std::size_t total = 12 + 8 + json.size() + 8 + bin.size();
  return "glTF" + u32(2) + u32(static_cast<std::uint32_t>(total)) + u32(static_cast<std::uint32_t>(json.size())) + "JSON" + json +
         u32(claimed) + std::string("BIN\0", 4) + bin;
}

TEST(Hostile, GlbBinChunkPastTheEndIsRefusedBeforeParsing) {
  test::TempDir dir;
  EXPECT_EQ(error_of(dir.write("fine.glb", glb_triangle(44))), "no error");
  // 8 bytes more than the file holds: tinygltf checks the length without the chunk's 8-byte
  // header and copied the buffer from past the end (fuzz_gltf, issue 50).
  const std::string e = error_of(dir.write("past.glb", glb_triangle(52)));
  EXPECT_EQ(e.rfind("gltf.parse: ", 0), 0u) << e;
  EXPECT_NE(e.find("the BIN chunk's 52 bytes end at byte"), std::string::npos) << e;
}

TEST(Hostile, NodeChainsAreWalkedWithoutRecursion) {
  test::TempDir dir;
  // 200,000 nested nodes: the recursive walk overflowed the stack at ~8,100.
  const std::string path = dir.write("chain.gltf", gltf(chain(200000, false)));
  EXPECT_EQ(error_of(path), "no error");
  EXPECT_EQ(read_model(path).mesh.triangles.size(), 1u);
}

TEST(Hostile, NodeGraphsThatAreNotTreesAreRefused) {
  test::TempDir dir;
  // Each node names the next twice: 2^40 instances from a 2 KB file.
  const std::string dag = error_of(dir.write("dag.gltf", gltf(chain(41, true))));
  EXPECT_EQ(dag.rfind("gltf.node_tree: ", 0), 0u) << dag;
  EXPECT_NE(dag.find("nodes[40]: is reached twice (from nodes[39].children)"), std::string::npos) << dag;
  std::string shared = gltf(R"([{"children":[2]},{"children":[2]},{"mesh":0}])");
  shared.replace(shared.find(R"("nodes":[0])"), 11, R"("nodes":[0,1])");
  const std::string two = error_of(dir.write("two.gltf", shared));
  EXPECT_EQ(two.rfind("gltf.node_tree: ", 0), 0u) << two;
  const std::string cycle = error_of(dir.write("cycle.gltf", gltf(R"([{"children":[1]},{"children":[0],"mesh":0}])")));
  EXPECT_EQ(cycle.rfind("gltf.node_cycle: ", 0), 0u) << cycle;
}

TEST(Hostile, InstancesPastTheMemoryLimitAreRefusedBeforeReading) {
  test::TempDir dir;
  std::string nodes = R"([{"children":[)";
  for (int i = 1; i <= 10000; ++i) nodes += (i > 1 ? "," : "") + std::to_string(i);
  nodes += "]}";
  for (int i = 1; i <= 10000; ++i) nodes += R"(,{"mesh":0})";
  const std::string path = dir.write("many.gltf", gltf(nodes + "]"));
  ReadOptions o;
  o.memory_limit = 1 << 20;
  const std::string e = error_of(path, o);
  EXPECT_EQ(e.rfind("gltf.memory: ", 0), 0u) << e;
  EXPECT_NE(e.find("10000 mesh instances"), std::string::npos) << e;
  EXPECT_NE(e.find("only 1 MB is allowed (--max-memory)"), std::string::npos) << e;
  o.memory_limit = 64 << 20;
  EXPECT_EQ(error_of(path, o), "no error");
}

TEST(Hostile, HugeAccessorCountsAreBadInput) {
  test::TempDir dir;
  for (const char* count : {"4611686018427387904", "1000000000"}) {
    const std::string e = error_of(dir.write("count.gltf", gltf(R"([{"mesh":0}])", "", kTriangleData, count)));
    EXPECT_TRUE(e.rfind("gltf.memory: ", 0) == 0 || e.rfind("gltf.accessor_bounds: ", 0) == 0) << e;
  }
  ReadOptions unlimited;
  unlimited.memory_limit = SIZE_MAX;  // the accessor's own check, past the memory check
  const std::string e = error_of(dir.write("count.gltf", gltf(R"([{"mesh":0}])", "", kTriangleData, "4611686018427387904")), unlimited);
  EXPECT_EQ(e.rfind("gltf.accessor_bounds: ", 0), 0u) << e;
}

TEST(Hostile, ImagesAreBudgetedFromTheirHeadersBeforeDecoding) {
  test::TempDir dir;
  dir.write("huge.png", png_header(16384));
  std::string text = gltf(R"([{"mesh":0}])", textured("huge.png", 8));
  const std::string path = dir.write("huge.gltf", text);
  ReadOptions o;
  o.memory_limit = std::size_t{2} << 30;
  const std::string e = error_of(path, o);
  EXPECT_EQ(e.rfind("gltf.memory: ", 0), 0u) << e;
  EXPECT_NE(e.find("8 images would need about 16 GB"), std::string::npos) << e;
  // The same through OBJ + MTL: the image's header is read before it is decoded.
  dir.write("huge.mtl", "newmtl m\nmap_Kd huge.png\n");
  const std::string obj = dir.write("huge.obj", "mtllib huge.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  o.memory_limit = 512 << 20;
  const std::string m = error_of(obj, o);
  EXPECT_EQ(m.rfind("mtl.memory: ", 0), 0u) << m;
  ImageHeader h = *image_header(reinterpret_cast<const std::uint8_t*>(png_header(300).data()), 33);
  EXPECT_EQ(h.width, 300u);
  EXPECT_EQ(decoded_image_bytes(h), 300u * 300u * 4u);
}

// BMP and TGA headers give their sides too (a TGA has no magic number: its fields' legal values).
TEST(Hostile, BmpAndTgaHeadersGiveTheirSides) {
  std::uint8_t bmp[26] = {'B', 'M'};
  bmp[14] = 40;                                      // BITMAPINFOHEADER
  bmp[18] = 0x00, bmp[19] = 0x40;                    // width 16384
  bmp[22] = 0x00, bmp[23] = 0xC0, bmp[24] = bmp[25] = 0xFF;  // height -16384: top-down
  const std::optional<ImageHeader> b = image_header(bmp, sizeof bmp);
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->width, 16384u);
  EXPECT_EQ(b->height, 16384u);
  std::uint8_t tga[18] = {0, 0, 2};                  // no colour map, true colour
  tga[12] = tga[13] = 0xFF, tga[14] = tga[15] = 0xFF, tga[16] = 32;  // 65535 x 65535, 32 bits
  const std::optional<ImageHeader> t = image_header(tga, sizeof tga);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(decoded_image_bytes(*t), 65535ull * 65535ull * 4ull);
  tga[16] = 7;  // no such pixel depth: not a TGA header
  EXPECT_FALSE(image_header(tga, sizeof tga).has_value());
}

// The message of a reference leading outside must not tell whether its target exists.
TEST(Hostile, ReferencesOutsideTheAssetsFolderAreRefused) {
  test::TempDir dir;
  fs::create_directories(dir.path("asset/sub"));
  // 42 bytes that would bake as a triangle: the outside file a reader must not take.
  const std::string secret(std::string("\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\x01\0\x02\0", 42));
  dir.write("secret.bin", secret);
  dir.write("asset/inside.bin", secret);
  const std::string outside_abs = fs::canonical(dir.path("secret.bin")).string();
  fs::create_symlink(outside_abs, dir.path("asset/link.bin"));
  fs::create_symlink("..", dir.path("asset/sub/up"));
  for (const std::string& uri : std::vector<std::string>{"../secret.bin", "%2e%2e/secret.bin", "sub/../../secret.bin", outside_abs, "link.bin",
                                "sub/up/../secret.bin", "sub/up/inside.bin/../../secret.bin", "%2e%2e%00/secret.bin"}) {
    const std::string e = error_of(dir.write("asset/a.gltf", gltf(R"([{"mesh":0}])", "", uri)));
    EXPECT_EQ(e.rfind("gltf.outside_asset: ", 0), 0u) << uri << ": " << e;
    EXPECT_NE(e.find("'" + uri + "' leads outside the asset's folder"), std::string::npos) << e;
    // The same words for a target that does not exist.
    if (uri.find("secret") == std::string::npos) continue;
    std::string missing = uri;
    missing.replace(missing.find("secret"), 6, "absent");
    const std::string m = error_of(dir.write("asset/a.gltf", gltf(R"([{"mesh":0}])", "", missing)));
    std::string expected = e;
    expected.replace(expected.find("secret"), 6, "absent");
    EXPECT_EQ(m, expected);
  }
  // Inside the folder, through a symlink that stays inside, it reads; a wider root allows more.
  EXPECT_EQ(error_of(dir.write("asset/a.gltf", gltf(R"([{"mesh":0}])", "", "sub/up/inside.bin"))), "no error");
  ReadOptions wide;
  wide.asset_root = dir.path("");
  EXPECT_EQ(error_of(dir.write("asset/a.gltf", gltf(R"([{"mesh":0}])", "", "../secret.bin")), wide), "no error");
  // Nothing outside in the batch's content key either.
  dir.write("asset/k.gltf", gltf(R"([{"mesh":0}])", textured("../secret.png", 1), "inside.bin"));
  const std::vector<InputDependency> deps = input_dependencies(dir.path("asset/k.gltf"));
  ASSERT_EQ(deps.size(), 1u);
  EXPECT_EQ(deps[0].name, "inside.bin");
}

TEST(Hostile, ReferencesToFoldersAndFifosAreRefused) {
  test::TempDir dir;
  fs::create_directories(dir.path("folder"));
  ASSERT_EQ(::mkfifo(dir.path("fifo.bin").c_str(), 0600), 0);
  for (const char* uri : {"folder", "fifo.bin"}) {
    const std::string e = error_of(dir.write("a.gltf", gltf(R"([{"mesh":0}])", "", uri)));
    EXPECT_EQ(e.rfind("gltf.not_regular_file: ", 0), 0u) << e;
  }
  dir.write("m.mtl", "newmtl m\nmap_Kd fifo.bin\n");
  const std::string e = error_of(dir.write("a.obj", "mtllib m.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(e.rfind("mtl.not_regular_file: ", 0), 0u) << e;
}

TEST(Hostile, ObjReferencesOutsideTheAssetsFolderAreRefused) {
  test::TempDir dir;
  fs::create_directories(dir.path("asset"));
  dir.write("outside.mtl", "newmtl m\nKd 1 0 0\n");
  dir.write("outside.png", png_header(4));
  const std::string faces = "usemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string a = error_of(dir.write("asset/a.obj", "mtllib ../outside.mtl\n" + faces));
  EXPECT_EQ(a.rfind("obj.outside_asset: ", 0), 0u) << a;
  EXPECT_NE(a.find("line 1: '../outside.mtl' leads outside"), std::string::npos) << a;
  dir.write("asset/in.mtl", "newmtl m\nmap_Kd ..\\outside.png\n");
  const std::string b = error_of(dir.write("asset/b.obj", "mtllib in.mtl\n" + faces));
  EXPECT_EQ(b.rfind("mtl.outside_asset: ", 0), 0u) << b;
  EXPECT_TRUE(input_dependencies(dir.path("asset/a.obj")).empty());
}

// Sampling is sized before it draws: an LDI whose layers would take more than the limit is
// refused (it was a std::bad_alloc inside the peeling's parallel loop: SIGABRT).
TEST(Hostile, SamplingPastTheMemoryLimitIsRefusedBeforeDrawing) {
  test::TempDir dir;
  const TriangleMesh mesh = read_model(dir.write("t.gltf", gltf())).mesh;
  SampleOptions o;
  o.ldi_size = 16000;
  o.memory_limit = 256 << 20;
  try {
    sample_mesh(mesh, o, "t.gltf");
    ADD_FAILURE() << "sampled";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), "sample.memory") << e.what();
    EXPECT_NE(std::string(e.what()).find("sampling its 1 triangles at LDI 16000 would need about"), std::string::npos) << e.what();
  }
  o.ldi_size = 64;
  EXPECT_GT(sample_mesh(mesh, o, "t.gltf").size(), 100u);
}

TEST(Hostile, ParallelErrorsKeepTheFirstIterationsException) {
  ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < 64; ++i)
    errors.run(i, [&] {
      if (i == 40 || i == 7) throw InputError("test.error", "f", "", std::to_string(i));
    });
  try {
    errors.rethrow();
    ADD_FAILURE() << "nothing rethrown";
  } catch (const InputError& e) {
    EXPECT_EQ(e.detail(), "7");
  }
}

}  // namespace
}  // namespace qf
