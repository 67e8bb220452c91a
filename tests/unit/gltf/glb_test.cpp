// The .glb writer: structure, extension contents, embedded PNGs, determinism. Read back with
// tinygltf's loader.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "analysis/analysis.h"
#include "core/error.h"
#include "domains/merge.h"
#include "gltf/glb.h"
#include "primitives/texture.h"
#include "runtime_gl/loader.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

ImpostorLevel octahedron_faces() {
  const PointSet p = generate_shape("octahedron");
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  const SparseMatrix psi = merge_domains(basis_at_level(h, h.level_count() - 2), p.positions);
  const Domains d = make_domains(psi);
  const std::vector<SupportRect> rects = support_rectangles(p.positions, p.normals, p.radii, psi, d);
  std::vector<Texture> textures;
  for (const SupportRect& r : rects) textures.push_back(resample_texture(p.positions, p.colors, p.normals, p.radii, psi, d, r));
  return make_impostor_level(h.level_count() - 2, rects, textures, d);
}

tinygltf::Model load(const std::vector<std::uint8_t>& glb) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromMemory(&m, &err, &warn, glb.data(), static_cast<unsigned>(glb.size()))) << err;
  EXPECT_TRUE(err.empty()) << err;
  return m;
}

// One of the extension's arrays: the values of the accessor its key names (unsigned integers of
// the narrowest type, or floats), in a bufferView with no target (neither vertices nor indices).
std::vector<double> extension_array(const tinygltf::Model& m, const char* key) {
  const tinygltf::Value& index = m.extensions.at(kImpostorExtension).Get(key);
  EXPECT_TRUE(index.IsInt()) << key;
  const tinygltf::Accessor& a = m.accessors.at(static_cast<std::size_t>(index.GetNumberAsInt()));
  const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  EXPECT_EQ(v.target, 0) << key;
  EXPECT_EQ(a.type, TINYGLTF_TYPE_SCALAR) << key;
  const unsigned char* p = m.buffers.at(0).data.data() + v.byteOffset + a.byteOffset;
  std::vector<double> out;
  for (std::size_t i = 0; i < a.count; ++i) {
    switch (a.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out.push_back(p[i]); break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: out.push_back(reinterpret_cast<const std::uint16_t*>(p)[i]); break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: out.push_back(reinterpret_cast<const std::uint32_t*>(p)[i]); break;
      case TINYGLTF_COMPONENT_TYPE_FLOAT: out.push_back(reinterpret_cast<const float*>(p)[i]); break;
      default: ADD_FAILURE() << key << ": component type " << a.componentType;
    }
  }
  return out;
}

TEST(Glb, QuadsMaterialsAndExtension) {
  const ImpostorLevel level = octahedron_faces();
  ASSERT_EQ(level.quads.size(), 8u);
  const std::vector<std::uint8_t> glb = encode_glb(level);
  const tinygltf::Model m = load(glb);
  ASSERT_EQ(m.meshes.size(), 1u);
  ASSERT_EQ(m.meshes[0].primitives.size(), level.atlas.images.size());
  const tinygltf::Primitive& prim = m.meshes[0].primitives[0];
  EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
  EXPECT_EQ(m.accessors[static_cast<std::size_t>(prim.attributes.at("POSITION"))].count, 4u * 8u);
  EXPECT_EQ(m.accessors[static_cast<std::size_t>(prim.indices)].count, 6u * 8u);
  // Indices as uint16 (a level has a few thousand vertices at most); normal, tangent and UVs
  // quantized (KHR_mesh_quantization), each vertex's within half a step of the float.
  EXPECT_EQ(m.accessors[static_cast<std::size_t>(prim.indices)].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  const int types[] = {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
  const char* names[] = {"NORMAL", "TANGENT", "TEXCOORD_0"};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(prim.attributes.count(names[i])) << names[i];
    const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(prim.attributes.at(names[i]))];
    EXPECT_EQ(a.componentType, types[i]) << names[i];
    EXPECT_TRUE(a.normalized) << names[i];
  }
  const tinygltf::Accessor& na = m.accessors[static_cast<std::size_t>(prim.attributes.at("NORMAL"))];
  const tinygltf::BufferView& nv = m.bufferViews[static_cast<std::size_t>(na.bufferView)];
  EXPECT_EQ(nv.byteStride, 4u);  // 3 bytes padded: vertex attributes are 4-byte aligned
  const auto* n0 = reinterpret_cast<const std::int8_t*>(m.buffers[0].data.data() + nv.byteOffset);
  std::size_t first = 0;  // primitive 0 holds the quads of atlas image 0, in order
  while (level.atlas.tiles[first].atlas != 0) ++first;
  const Vec3f want = level.quads[first].normal;
  EXPECT_NEAR(n0[0] / 127.0f, want.x, 0.5f / 127);
  EXPECT_NEAR(n0[1] / 127.0f, want.y, 0.5f / 127);
  EXPECT_NEAR(n0[2] / 127.0f, want.z, 0.5f / 127);
  // Colour and normal atlases, embedded as PNG.
  const tinygltf::Material& mat = m.materials[static_cast<std::size_t>(prim.material)];
  EXPECT_EQ(mat.alphaMode, "MASK");
  EXPECT_FLOAT_EQ(static_cast<float>(mat.alphaCutoff), 0.2f);
  ASSERT_GE(mat.pbrMetallicRoughness.baseColorTexture.index, 0);
  ASSERT_GE(mat.normalTexture.index, 0);
  const tinygltf::Image& img = m.images[static_cast<std::size_t>(m.textures[static_cast<std::size_t>(mat.pbrMetallicRoughness.baseColorTexture.index)].source)];
  EXPECT_EQ(img.mimeType, "image/png");
  EXPECT_EQ(img.width, level.atlas.widths[0]);
  EXPECT_EQ(img.height, level.atlas.heights[0]);
  // The normal map at half the atlas's size, in the same texture coordinates.
  const tinygltf::Image& normal = m.images[static_cast<std::size_t>(m.textures[static_cast<std::size_t>(mat.normalTexture.index)].source)];
  EXPECT_EQ(normal.width, level.atlas.widths[0] / 2);
  EXPECT_EQ(normal.height, level.atlas.heights[0] / 2);
  // The extension: optional, with one entry per quad and the octahedron's 12 edges (24 half-edges).
  ASSERT_EQ(m.extensionsUsed, (std::vector<std::string>{kQuantizationExtension, kImpostorExtension}));
  EXPECT_EQ(m.extensionsRequired, std::vector<std::string>{kQuantizationExtension});
  const tinygltf::Value& ext = m.extensions.at(kImpostorExtension);
  EXPECT_EQ(ext.Get("quadCount").GetNumberAsInt(), 8);
  EXPECT_EQ(ext.Get("blend").Get<std::string>(), "additive_sorted_lock_by_depth");
  EXPECT_DOUBLE_EQ(ext.Get("alphaRef").GetNumberAsDouble(), 0.1);
  // Its arrays are accessors: domains of a few quads in bytes, errors as floats.
  const std::vector<double> domain = extension_array(m, "domain"), error = extension_array(m, "error");
  EXPECT_EQ(m.accessors.at(static_cast<std::size_t>(ext.Get("domain").GetNumberAsInt())).componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
  ASSERT_EQ(domain.size(), 8u);
  ASSERT_EQ(error.size(), 8u);
  for (std::size_t k = 0; k < 8; ++k) {
    const auto q = std::find_if(level.quads.begin(), level.quads.end(), [&](const SupportRect& r) { return r.domain == domain[k]; });
    ASSERT_NE(q, level.quads.end());
    EXPECT_EQ(error[k], static_cast<float>(q->error));
  }
  // The planes and atlas rectangles are in the vertices, not repeated in the extension.
  EXPECT_FALSE(ext.Has("center"));
  EXPECT_FALSE(ext.Has("normal"));
  EXPECT_FALSE(ext.Has("atlasRect"));
  const std::vector<double> offsets = extension_array(m, "neighborOffsets"), neighbors = extension_array(m, "neighbors");
  ASSERT_EQ(offsets.size(), 9u);
  EXPECT_EQ(offsets.front(), 0);
  EXPECT_EQ(offsets.back(), 24);
  EXPECT_EQ(neighbors.size(), 24u);  // every face of the octahedron has three neighbours
  for (std::size_t k = 0; k < 8; ++k) EXPECT_EQ(offsets[k + 1] - offsets[k], 3) << k;
  EXPECT_FALSE(ext.Has("alphaExponent"));  // Psi itself
  // Same input, same bytes.
  EXPECT_EQ(encode_glb(level), glb);
  // A level whose alpha is stored with an exponent says so, for runtimes that blend Psi.
  ImpostorLevel sharp = level;
  sharp.alpha_exponent = 2;
  EXPECT_DOUBLE_EQ(load(encode_glb(sharp)).extensions.at(kImpostorExtension).Get("alphaExponent").GetNumberAsDouble(), 2.0);
}

// The runtime reads the graph from the accessors; a file of quasiflat 0.7 or earlier, whose arrays
// were JSON, or one whose accessor index names nothing, is refused with a clear error.
TEST(Glb, RuntimeReadsTheGraphAccessorsAndRefusesTheJsonArrays) {
  const ImpostorLevel level = octahedron_faces();
  const render::BakedScene scene = render::load_baked(encode_glb(level), "level.glb");
  EXPECT_EQ(scene.impostor.offsets.size(), 9u);
  EXPECT_EQ(scene.impostor.neighbors.size(), 24u);
  const auto rewritten = [&](const char* key, tinygltf::Value value) {
    tinygltf::Model m = load(encode_glb(level));
    tinygltf::Value::Object ext = m.extensions.at(kImpostorExtension).Get<tinygltf::Value::Object>();
    ext[key] = std::move(value);
    m.extensions[kImpostorExtension] = tinygltf::Value(ext);
    std::ostringstream out;
    tinygltf::TinyGLTF().WriteGltfSceneToStream(&m, out, false, true);
    const std::string bytes = out.str();
    return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
  };
  tinygltf::Value::Array old_rows;
  for (int k = 0; k <= 8; ++k) old_rows.push_back(tinygltf::Value(3 * k));
  try {
    render::load_baked(rewritten("neighborOffsets", tinygltf::Value(old_rows)), "old.glb");
    ADD_FAILURE() << "a JSON array was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), "render.gltf.extension");
    EXPECT_NE(std::string(e.what()).find("bake the asset again"), std::string::npos) << e.what();
  }
  EXPECT_THROW(render::load_baked(rewritten("neighbors", tinygltf::Value(999)), "bad.glb"), InputError);
}

// A file of several levels (MSFT_lod) carries their meshes and images, not the extension's arrays,
// which only a level's own file has: no accessor is left that nothing uses.
TEST(Glb, CombinedLevelsLeaveTheExtensionArraysBehind) {
  const std::vector<std::uint8_t> level = encode_glb(octahedron_faces());
  const tinygltf::Model part = load(level);
  const tinygltf::Model m = load(combine_lod_glb({&level, &level}, {0.1, 0}, "two"));
  std::set<int> used;
  for (const tinygltf::Mesh& mesh : m.meshes)
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      for (const auto& [name, accessor] : prim.attributes) used.insert(accessor);
      used.insert(prim.indices);
    }
  EXPECT_EQ(used.size(), m.accessors.size());
  EXPECT_EQ(m.accessors.size(), 2 * (part.accessors.size() - 4));  // domain, error, offsets, neighbours
  EXPECT_EQ(m.images.size(), 2 * part.images.size());
  EXPECT_FALSE(m.extensions.count(kImpostorExtension));
  const render::BakedScene scene = render::load_baked(combine_lod_glb({&level, &level}, {0.1, 0}, "two"), "two_lods.glb");
  ASSERT_EQ(scene.lods.size(), 2u);
  for (const render::BakedScene& lod : scene.lods) EXPECT_EQ(lod.impostor.items.size(), 8u);
}

// Quad k of the extension is the k-th quad of the mesh's primitives, also when the atlas spans
// several images and the packer (tallest tiles first) interleaves them: the runtime reads each
// quad's domain with the plane of its own vertices.
TEST(Glb, ExtensionQuadsFollowThePrimitives) {
  const PointSet p = generate_shape("octahedron");
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  const SparseMatrix psi = merge_domains(basis_at_level(h, h.level_count() - 2), p.positions);
  const Domains d = make_domains(psi);
  const std::vector<SupportRect> rects = support_rectangles(p.positions, p.normals, p.radii, psi, d);
  std::vector<Texture> textures;
  for (std::size_t k = 0; k < rects.size(); ++k) {
    // Odd quads' tiles taller, so the packer places them first and they fill the first 64 x 64
    // image (two 32 x 32 cells a row); the shorter even ones go to the second.
    Texture t;
    t.width = 28;
    t.height = k % 2 ? 28 : 12;
    t.texel = 0.02f;  // the quad's size: texels x texel
    t.rgba.assign(static_cast<std::size_t>(t.width * t.height * 4), 200);
    textures.push_back(t);
  }
  AtlasOptions small;
  small.max_side = 64;
  const ImpostorLevel level = make_impostor_level(h.level_count() - 2, rects, textures, d, small);
  ASSERT_GE(level.atlas.images.size(), 2u);
  ASSERT_NE(level.atlas.tiles[0].atlas, level.atlas.tiles[1].atlas);  // interleaved
  const render::BakedScene scene = render::load_baked(encode_glb(level), "interleaved.glb");
  const tinygltf::Model model = load(encode_glb(level));
  const std::vector<double> domains = extension_array(model, "domain");
  ASSERT_EQ(scene.impostor.items.size(), level.quads.size());
  std::vector<bool> seen(level.quads.size(), false);
  std::uint32_t last_image = 0;
  for (std::size_t k = 0; k < level.quads.size(); ++k) {
    // The level's quad with this domain: its plane is what the runtime read for quad k.
    const auto domain = static_cast<std::uint32_t>(domains.at(k));
    std::size_t q = 0;
    while (q < level.quads.size() && level.quads[q].domain != domain) ++q;
    ASSERT_LT(q, level.quads.size());
    seen[q] = true;
    EXPECT_GE(level.atlas.tiles[q].atlas, last_image);  // images in order
    last_image = level.atlas.tiles[q].atlas;
    const render::Item& it = scene.impostor.items[k];
    EXPECT_LT(length(it.center - level.quads[q].center), 1e-5f) << k;
    EXPECT_GT(dot(it.normal, level.quads[q].normal), 0.9999f) << k;
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), static_cast<long>(level.quads.size()));
  // The graph in the file's order: each edge of the level between the quads of its two domains.
  const std::vector<std::uint32_t>& off = scene.impostor.offsets;
  ASSERT_EQ(off.size(), level.quads.size() + 1);
  EXPECT_EQ(scene.impostor.neighbors.size(), 2 * level.edges.size());
  std::set<std::pair<std::uint32_t, std::uint32_t>> file_edges, level_edges;
  for (std::size_t k = 0; k < level.quads.size(); ++k)
    for (std::uint32_t i = off[k]; i < off[k + 1]; ++i) {
      const auto a = static_cast<std::uint32_t>(domains.at(k));
      const auto b = static_cast<std::uint32_t>(domains.at(scene.impostor.neighbors[i]));
      file_edges.insert({std::min(a, b), std::max(a, b)});
    }
  for (const auto& e : level.edges) {
    const std::uint32_t a = level.quads[e[0]].domain, b = level.quads[e[1]].domain;
    level_edges.insert({std::min(a, b), std::max(a, b)});
  }
  EXPECT_EQ(file_edges, level_edges);
}

// A strip of `quads` unit squares (4 vertices each, unshared), so its vertex count is 4 x quads.
TriangleMesh square_strip(std::uint32_t quads) {
  TriangleMesh mesh;
  for (std::uint32_t k = 0; k < quads; ++k) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    const float x = static_cast<float>(k);
    mesh.positions.insert(mesh.positions.end(), {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}});
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
  }
  return mesh;
}

// Indices are uint16 while every vertex index is below 65535 (the restart value), uint32 above,
// and read back as written either way.
TEST(Glb, IndexWidthFollowsTheVertexCount) {
  for (const std::uint32_t quads : {16383u, 16384u}) {  // 65532 and 65536 vertices
    const TriangleMesh mesh = square_strip(quads);
    const tinygltf::Model m = load(encode_mesh_glb(mesh, false));
    const tinygltf::Accessor& a = m.accessors.at(static_cast<std::size_t>(m.meshes.at(0).primitives.at(0).indices));
    EXPECT_EQ(a.componentType, quads == 16383u ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) << quads;
    EXPECT_EQ(a.count, mesh.triangles.size() * 3);
  }
}

}  // namespace
}  // namespace qf
