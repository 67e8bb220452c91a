// The decoders of compressed glTF input (issue 51): meshopt views and Draco streams round-trip what
// their encoders wrote, and malformed data of every kind (each truncation, flipped bytes, broken
// rules, claimed counts) is refused with an exception, never a crash or an assertion: the label
// "readers" runs this under ASan + UBSan too.
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "gltf/draco.h"
#include "gltf/meshopt_decode.h"

namespace qf {
namespace {

// A 8 x 8 grid: 64 vertices of 3 floats and a pad (16 bytes), 98 triangles.
struct Grid {
  std::vector<float> vertices;  // x, y, z, 0
  std::vector<std::uint32_t> indices;
};
Grid grid() {
  Grid g;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) g.vertices.insert(g.vertices.end(), {x * 0.125f, y * 0.125f, (x * y) % 3 * 0.01f, 0.0f});
  for (std::uint32_t y = 0; y < 7; ++y)
    for (std::uint32_t x = 0; x < 7; ++x) {
      const std::uint32_t a = y * 8 + x;
      g.indices.insert(g.indices.end(), {a, a + 1, a + 9, a, a + 9, a + 8});
    }
  return g;
}

// Version 0 of the vertex codec, the one EXT_meshopt_compression defines (meshoptimizer 1.x writes
// version 1 unless told).
std::vector<std::uint8_t> encode_vertices(const Grid& g) {
  meshopt_encodeVertexVersion(0);
  std::vector<std::uint8_t> out(meshopt_encodeVertexBufferBound(64, 16));
  out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), g.vertices.data(), 64, 16));
  return out;
}

std::vector<std::uint8_t> encode_triangles(const Grid& g) {
  std::vector<std::uint8_t> out(meshopt_encodeIndexBufferBound(g.indices.size(), 64));
  out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), g.indices.data(), g.indices.size()));
  return out;
}

TEST(MeshoptDecode, RoundTripsVerticesAndTriangles) {
  const Grid g = grid();
  const std::vector<std::uint8_t> v = encode_vertices(g), t = encode_triangles(g);
  const std::vector<std::uint8_t> dv = meshopt_decode(v.data(), v.size(), {"ATTRIBUTES", "NONE", 64, 16});
  ASSERT_EQ(dv.size(), g.vertices.size() * 4);
  EXPECT_EQ(std::memcmp(dv.data(), g.vertices.data(), dv.size()), 0);
  const std::vector<std::uint8_t> dt = meshopt_decode(t.data(), t.size(), {"TRIANGLES", "NONE", g.indices.size(), 4});
  std::vector<std::uint32_t> idx(g.indices.size());
  std::memcpy(idx.data(), dt.data(), dt.size());
  // The index codec may rotate a triangle's corners; each triangle keeps its corners and winding.
  for (std::size_t i = 0; i < idx.size(); i += 3) {
    const std::uint32_t* a = &g.indices[i];
    const std::uint32_t* b = &idx[i];
    const bool same = (b[0] == a[0] && b[1] == a[1] && b[2] == a[2]) || (b[0] == a[1] && b[1] == a[2] && b[2] == a[0]) ||
                      (b[0] == a[2] && b[1] == a[0] && b[2] == a[1]);
    EXPECT_TRUE(same) << "triangle " << i / 3;
  }
}

TEST(MeshoptDecode, OctahedralFilterGivesUnitNormals) {
  std::vector<float> normals;
  for (int i = 0; i < 16; ++i) {
    const float a = i * 0.4f, b = i * 0.7f;
    normals.insert(normals.end(), {std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), std::cos(b), 0.0f});
  }
  std::vector<std::int8_t> packed(16 * 4);
  meshopt_encodeFilterOct(packed.data(), 16, 4, 8, normals.data());
  meshopt_encodeVertexVersion(0);
  std::vector<std::uint8_t> stream(meshopt_encodeVertexBufferBound(16, 4));
  stream.resize(meshopt_encodeVertexBuffer(stream.data(), stream.size(), packed.data(), 16, 4));
  const std::vector<std::uint8_t> d = meshopt_decode(stream.data(), stream.size(), {"ATTRIBUTES", "OCTAHEDRAL", 16, 4});
  for (int i = 0; i < 16; ++i) {
    const auto* n = reinterpret_cast<const std::int8_t*>(&d[static_cast<std::size_t>(i) * 4]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(n[c] / 127.0f, normals[static_cast<std::size_t>(i * 4 + c)], 0.03f) << i;
  }
}

// Version 1 of the vertex codec (KHR_meshopt_compression's, which meshoptimizer 1.x decodes) is no
// EXT_meshopt_compression stream: refused by its header byte, not read.
TEST(MeshoptDecode, VertexCodecVersion1IsRefused) {
  const Grid g = grid();
  meshopt_encodeVertexVersion(1);
  std::vector<std::uint8_t> v(meshopt_encodeVertexBufferBound(64, 16));
  v.resize(meshopt_encodeVertexBuffer(v.data(), v.size(), g.vertices.data(), 64, 16));
  ASSERT_EQ(meshopt_decodeVertexVersion(v.data(), v.size()), 1);
  try {
    meshopt_decode(v.data(), v.size(), {"ATTRIBUTES", "NONE", 64, 16});
    ADD_FAILURE() << "a version-1 stream was decoded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("0xa0"), std::string::npos) << e.what();
  }
}

TEST(MeshoptDecode, EveryTruncationIsRefused) {
  const Grid g = grid();
  const std::vector<std::uint8_t> v = encode_vertices(g), t = encode_triangles(g);
  for (std::size_t n = 0; n < v.size(); ++n)
    EXPECT_THROW(meshopt_decode(v.data(), n, {"ATTRIBUTES", "NONE", 64, 16}), std::runtime_error) << n;
  for (std::size_t n = 0; n < t.size(); ++n)
    EXPECT_THROW(meshopt_decode(t.data(), n, {"TRIANGLES", "NONE", g.indices.size(), 4}), std::runtime_error) << n;
}

TEST(MeshoptDecode, FlippedBytesNeverCrash) {
  const Grid g = grid();
  const std::vector<std::uint8_t> v = encode_vertices(g), t = encode_triangles(g);
  std::mt19937 rng(51);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<std::uint8_t> a = v, b = t;
    a[rng() % a.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    b[rng() % b.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    try {
      meshopt_decode(a.data(), a.size(), {"ATTRIBUTES", trial % 2 ? "EXPONENTIAL" : "NONE", 64, 16});
    } catch (const std::runtime_error&) {
    }
    try {
      meshopt_decode(b.data(), b.size(), {trial % 2 ? "INDICES" : "TRIANGLES", "NONE", g.indices.size(), 4});
    } catch (const std::runtime_error&) {
    }
  }
}

// Rules meshoptimizer asserts (a Debian build keeps its asserts): refused before it is called.
TEST(MeshoptDecode, BrokenRulesAreRefused) {
  const std::vector<std::uint8_t> any(64, 0);
  for (const MeshoptView& v : std::vector<MeshoptView>{{"ATTRIBUTES", "NONE", 4, 6},
                                                       {"ATTRIBUTES", "NONE", 4, 260},
                                                       {"ATTRIBUTES", "NONE", 4, 0},
                                                       {"TRIANGLES", "NONE", 4, 2},
                                                       {"TRIANGLES", "NONE", 3, 8},
                                                       {"INDICES", "NONE", 3, 1},
                                                       {"TRIANGLES", "OCTAHEDRAL", 3, 4},
                                                       {"ATTRIBUTES", "OCTAHEDRAL", 4, 12},
                                                       {"ATTRIBUTES", "QUATERNION", 4, 4},
                                                       {"ATTRIBUTES", "SPHERICAL", 4, 4},
                                                       {"SPLINES", "NONE", 4, 4},
                                                       {"ATTRIBUTES", "NONE", 1ull << 62, 16}})
    EXPECT_THROW(meshopt_decode(any.data(), any.size(), v), std::runtime_error) << v.mode << " " << v.filter << " " << v.stride;
  EXPECT_EQ(meshopt_decoded_bytes({"ATTRIBUTES", "NONE", 1ull << 62, 16}), 0u);  // overflow: 0, refused above
}

DracoOutput draco_grid() {
  const Grid g = grid();
  DracoInput in;
  for (std::uint32_t i : g.indices) in.positions.insert(in.positions.end(), &g.vertices[i * 4], &g.vertices[i * 4 + 3]);
  return draco_compress(in);
}

TEST(DracoDecode, PeeksTheClaimedCountsAndDecodes) {
  const DracoOutput d = draco_grid();
  const DracoCounts n = draco_peek_counts(d.bytes.data(), d.bytes.size());
  EXPECT_EQ(n.faces, 98u);
  EXPECT_GE(n.points, d.vertices);
  const DracoTypedMesh m = draco_decode_typed(d.bytes.data(), d.bytes.size(), {{d.position_id, 3, 5126}});
  EXPECT_EQ(m.points, d.vertices);
  EXPECT_EQ(m.corners.size(), 98u * 3);
  EXPECT_EQ(m.attributes.at(d.position_id).component_type, 5126);
  EXPECT_EQ(m.attributes.at(d.position_id).bytes.size(), d.vertices * 12);
  EXPECT_THROW(draco_decode_typed(d.bytes.data(), d.bytes.size(), {{d.position_id + 7, 3, 5126}}), std::runtime_error);
}

TEST(DracoDecode, TruncationsAndFlippedBytesNeverCrash) {
  const DracoOutput d = draco_grid();
  for (std::size_t n = 0; n < d.bytes.size(); ++n) {
    try {
      draco_peek_counts(d.bytes.data(), n);
      draco_decode_typed(d.bytes.data(), n, {{d.position_id, 3, 5126}});
    } catch (const std::runtime_error&) {
    }
  }
  std::mt19937 rng(51);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<std::uint8_t> b = d.bytes;
    b[11 + rng() % (b.size() - 11)] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    try {
      const DracoCounts n = draco_peek_counts(b.data(), b.size());
      if (n.faces > 1000) continue;  // a claim the readers' memory check would refuse first
      draco_decode_typed(b.data(), b.size(), {{d.position_id, 3, 5126}});
    } catch (const std::runtime_error&) {
    }
  }
}

TEST(DracoDecode, HeaderClaimsReadWithoutDraco) {
  // Edgebreaker 2.2: traversal 0, 3 vertices, 2^30 - 1 faces (varints), as tests/hostile writes it.
  std::vector<std::uint8_t> s{'D', 'R', 'A', 'C', 'O', 2, 2, 1, 1, 0, 0, 0, 3, 0xFF, 0xFF, 0xFF, 0xFF, 0x03};
  EXPECT_EQ(draco_peek_counts(s.data(), s.size()).faces, (1u << 30) - 1);
  s[7] = 0;  // a point cloud
  EXPECT_THROW(draco_peek_counts(s.data(), s.size()), std::runtime_error);
  s[7] = 1;
  s[10] = 0x80;  // metadata flag with no metadata after it: cut short
  s.resize(12);
  EXPECT_THROW(draco_peek_counts(s.data(), s.size()), std::runtime_error);
  const std::uint8_t varint_too_long[] = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x01};
  EXPECT_THROW(draco_peek_counts(varint_too_long, sizeof(varint_too_long)), std::runtime_error);
}

}  // namespace
}  // namespace qf
