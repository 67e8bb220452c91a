// The .glb writer: structure, extension contents, embedded PNGs, determinism. Read back with
// tinygltf's loader.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "analysis/analysis.h"
#include "domains/merge.h"
#include "gltf/glb.h"
#include "primitives/texture.h"
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
  for (const char* attr : {"NORMAL", "TANGENT", "TEXCOORD_0"}) EXPECT_TRUE(prim.attributes.count(attr)) << attr;
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
  // The extension: optional, with one entry per quad and the octahedron's 12 edges (24 half-edges).
  ASSERT_EQ(m.extensionsUsed, std::vector<std::string>{kImpostorExtension});
  EXPECT_TRUE(m.extensionsRequired.empty());
  const tinygltf::Value& ext = m.extensions.at(kImpostorExtension);
  EXPECT_EQ(ext.Get("quadCount").GetNumberAsInt(), 8);
  EXPECT_EQ(ext.Get("blend").Get<std::string>(), "additive_sorted_lock_by_depth");
  EXPECT_DOUBLE_EQ(ext.Get("alphaRef").GetNumberAsDouble(), 0.1);
  EXPECT_EQ(ext.Get("center").ArrayLen(), 24u);
  EXPECT_EQ(ext.Get("atlasRect").ArrayLen(), 40u);
  EXPECT_EQ(ext.Get("neighborOffsets").ArrayLen(), 9u);
  EXPECT_EQ(ext.Get("neighbors").ArrayLen(), 24u);
  EXPECT_FALSE(ext.Has("alphaExponent"));  // Psi itself
  // Same input, same bytes.
  EXPECT_EQ(encode_glb(level), glb);
  // A level whose alpha is stored with an exponent says so, for runtimes that blend Psi.
  ImpostorLevel sharp = level;
  sharp.alpha_exponent = 2;
  EXPECT_DOUBLE_EQ(load(encode_glb(sharp)).extensions.at(kImpostorExtension).Get("alphaExponent").GetNumberAsDouble(), 2.0);
}

}  // namespace
}  // namespace qf
