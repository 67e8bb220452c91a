// .glb writer on tinygltf 2.7 (gltf-notes.md section 6 for its pitfalls: primitive mode, empty
// arrays, extensionsUsed by hand, images through bufferViews).
#include "gltf/glb.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "core/color.h"
#include "core/gltf_component.h"
#include "gltf/draco.h"
#include "gltf/glb_model.h"
#include "gltf/png.h"
#include "primitives/mip_levels.h"

namespace qf {
namespace glb_model {

using tinygltf::Value;

// Appends raw bytes to buffer 0 (4-byte aligned) and returns a bufferView over them.
int add_view(tinygltf::Model& m, const void* data, std::size_t bytes, int target) {
  std::vector<unsigned char>& buf = m.buffers[0].data;
  buf.resize((buf.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = buf.size();
  v.byteLength = bytes;
  if (target) v.target = target;
  const auto* p = static_cast<const unsigned char*>(data);
  buf.insert(buf.end(), p, p + bytes);
  m.bufferViews.push_back(v);
  return static_cast<int>(m.bufferViews.size() - 1);
}

// A float VECn accessor with exact min/max (of the float32 values as stored).
// `target`: the bufferView's (vertex data; 0 for other data).
int add_floats(tinygltf::Model& m, const std::vector<float>& v, int components, int type, bool bounds, int target) {
  tinygltf::Accessor a;
  a.bufferView = add_view(m, v.data(), v.size() * sizeof(float), target);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = v.size() / static_cast<std::size_t>(components);
  a.type = type;
  if (bounds) {
    a.minValues.assign(static_cast<std::size_t>(components), INFINITY);
    a.maxValues.assign(static_cast<std::size_t>(components), -INFINITY);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const auto c = i % static_cast<std::size_t>(components);
      a.minValues[c] = std::min(a.minValues[c], canonical_double(v[i]));
      a.maxValues[c] = std::max(a.maxValues[c], canonical_double(v[i]));
    }
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

// A normalized integer VECn accessor over `bytes` (KHR_mesh_quantization), `count` elements of
// `stride` bytes each (padded to 4 bytes, as vertex attributes must be aligned).
int add_normalized(tinygltf::Model& m, const void* bytes, std::size_t count, int component_type, int type, int stride) {
  tinygltf::Accessor a;
  a.bufferView = add_view(m, bytes, count * static_cast<std::size_t>(stride), TINYGLTF_TARGET_ARRAY_BUFFER);
  const int element = gltf_component::size_of(component_type) * tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type));
  if (element != stride) m.bufferViews.back().byteStride = static_cast<std::size_t>(stride);
  a.componentType = component_type;
  a.normalized = true;
  a.count = count;
  a.type = type;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

// A SCALAR accessor of unsigned integers that are neither vertices nor indices (the extension's
// per-quad arrays): the narrowest component type that holds every value, so a level of a few
// hundred quads pays 1-2 bytes an entry; returns its index.
template <class T>
int add_scalars_as(tinygltf::Model& m, const std::vector<std::uint32_t>& v, int component_type) {
  const std::vector<T> narrow(v.begin(), v.end());
  tinygltf::Accessor a;
  a.bufferView = add_view(m, narrow.data(), narrow.size() * sizeof(T), 0);
  a.componentType = component_type;
  a.count = v.size();
  a.type = TINYGLTF_TYPE_SCALAR;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}
int add_unsigned(tinygltf::Model& m, const std::vector<std::uint32_t>& v) {
  const std::uint32_t top = v.empty() ? 0 : *std::max_element(v.begin(), v.end());
  if (top <= 0xff) return add_scalars_as<std::uint8_t>(m, v, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
  if (top <= 0xffff) return add_scalars_as<std::uint16_t>(m, v, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  return add_scalars_as<std::uint32_t>(m, v, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
}


std::vector<std::uint8_t> rgb_of(const std::vector<std::uint8_t>& rgba) {
  std::vector<std::uint8_t> rgb(rgba.size() / 4 * 3);
  for (std::size_t k = 0; k < rgba.size() / 4; ++k) std::copy_n(&rgba[4 * k], 3, &rgb[3 * k]);
  return rgb;
}

// `rgb_only` (PNG): the alpha channel is left out (normal maps, whose alpha is unused and 255: 12%
// fewer bytes for the bunny's finest normal atlas).
std::vector<std::uint8_t> png_bytes(const std::vector<std::uint8_t>& rgba, int w, int h, bool rgb_only) {
  if (!rgb_only) return encode_png(rgba.data(), w, h, 4);
  return encode_png(rgb_of(rgba).data(), w, h, 3);
}

// KTX2: the coverage-preserving chain (colour, at the MASK cutoff) or the plain one, encoded with
// the class's codec; normal maps in the encoder's normal-map mode, data linear.
std::vector<std::uint8_t> ktx2_bytes(const std::vector<std::uint8_t>& rgba, int w, int h, TextureClass cls,
                                     const GltfOptions& options) {
  MipOptions mip;
  mip.kind = cls == TextureClass::kNormal ? MipOptions::Kind::kNormal
             : cls == TextureClass::kData ? MipOptions::Kind::kLinear
                                          : MipOptions::Kind::kColor;
  if (cls == TextureClass::kColor && options.alpha_mode == "MASK") mip.alpha_cutoff = options.alpha_cutoff;
  Ktx2Options k;
  k.codec = cls == TextureClass::kColor || cls == TextureClass::kEmissive ? options.color_codec : options.normal_codec;
  k.srgb = cls == TextureClass::kColor || cls == TextureClass::kEmissive;
  k.normal_map = cls == TextureClass::kNormal;
  k.etc1s_quality = options.etc1s_quality;
  k.threads = options.threads;
  return encode_ktx2(mip_levels(TextureImage{w, h, rgba}, mip), k);
}

// WebP: the class's settings; colour keeps its alpha, the others are RGB as in the PNG path.
// Occlusion/roughness/metallic are data: lossless, whatever the normal maps' setting.
std::vector<std::uint8_t> webp_bytes(const std::vector<std::uint8_t>& rgba, int w, int h, TextureClass cls,
                                     const GltfOptions& options) {
  WebpOptions o = cls == TextureClass::kNormal ? options.webp_normal : options.webp_color;
  if (cls == TextureClass::kData) o = WebpOptions{}, o.lossless = true;
  if (cls == TextureClass::kColor) return encode_webp(rgba.data(), w, h, 4, o);
  return encode_webp(rgb_of(rgba).data(), w, h, 3, o);
}

// A texture's image in the options' format.
std::vector<std::uint8_t> encoded_image(const std::vector<std::uint8_t>& rgba, int w, int h, TextureClass cls, const GltfOptions& options) {
  if (options.textures == GltfOptions::Textures::kKtx2) return ktx2_bytes(rgba, w, h, cls, options);
  if (options.textures == GltfOptions::Textures::kWebp) return webp_bytes(rgba, w, h, cls, options);
  return png_bytes(rgba, w, h, cls != TextureClass::kColor);
}

// Adds an encoded image (encoded_image's, w x h texels) and a texture of it; returns the
// texture's index.
int add_encoded_texture(tinygltf::Model& m, const std::vector<std::uint8_t>& bytes, int w, int h, const std::string& name,
                        const GltfOptions& options, TextureCost* cost) {
  const bool ktx2 = options.textures == GltfOptions::Textures::kKtx2, webp = options.textures == GltfOptions::Textures::kWebp;
  tinygltf::Image img;
  img.name = name;
  img.mimeType = ktx2 ? "image/ktx2" : webp ? "image/webp" : "image/png";
  img.bufferView = add_view(m, bytes.data(), bytes.size(), 0);
  m.images.push_back(img);
  tinygltf::Texture t;
  const int source = static_cast<int>(m.images.size() - 1);
  // KHR_texture_basisu and EXT_texture_webp without a fallback: the texture names its image in the
  // extension alone, and the extension is required (the extensions' specs). A PNG fallback would
  // cost its bytes on top (docs/textures.md): WebP's only gain is bytes.
  if (ktx2) t.extensions[kBasisuExtension] = Value(Value::Object{{"source", Value(source)}});
  else if (webp) t.extensions[kWebpExtension] = Value(Value::Object{{"source", Value(source)}});
  else t.source = source;
  t.sampler = 0;
  m.textures.push_back(t);
  if (cost) {
    cost->file_bytes += bytes.size();
    cost->texels += static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    // Every mip level down to 1x1: RGBA8 texels (PNG and WebP decode to them, and the engine makes
    // the levels), or 4x4 blocks of 16 bytes (KTX2; a level under 4 texels a side still takes a
    // whole block).
    for (std::size_t lw = static_cast<std::size_t>(w), lh = static_cast<std::size_t>(h);; lw = std::max<std::size_t>(1, lw / 2), lh = std::max<std::size_t>(1, lh / 2)) {
      cost->gpu_bytes += ktx2 ? 16 * ((lw + 3) / 4) * ((lh + 3) / 4) : 4 * lw * lh;
      if (lw == 1 && lh == 1) break;
    }
  }
  return static_cast<int>(m.textures.size() - 1);
}

// Adds an image and a texture of it in the options' format; returns the texture's index.
int add_texture(tinygltf::Model& m, const std::vector<std::uint8_t>& rgba, int w, int h, const std::string& name,
                TextureClass cls, const GltfOptions& options, TextureCost* cost) {
  return add_encoded_texture(m, encoded_image(rgba, w, h, cls, options), w, h, name, options, cost);
}

}  // namespace glb_model

using namespace glb_model;

ImpostorLevel make_impostor_level(std::size_t level, const std::vector<SupportRect>& rects,
                                  const std::vector<Texture>& textures, const Domains& domains,
                                  const AtlasOptions& atlas_options) {
  ImpostorLevel out;
  out.level = level;
  out.quads = rects;
  for (const Texture& t : textures) {
    out.half_u.push_back(0.5f * static_cast<float>(t.width) * t.texel);
    out.half_v.push_back(0.5f * static_cast<float>(t.height) * t.texel);
  }
  out.atlas = pack_atlas(textures, atlas_options);
  std::vector<std::int64_t> quad_of(domains.count(), -1);
  for (std::size_t k = 0; k < rects.size(); ++k) quad_of[rects[k].domain] = static_cast<std::int64_t>(k);
  for (const auto& e : domains.edges)
    if (quad_of[e[0]] >= 0 && quad_of[e[1]] >= 0)
      out.edges.push_back({static_cast<std::uint32_t>(quad_of[e[0]]), static_cast<std::uint32_t>(quad_of[e[1]])});
  return out;
}

namespace glb_model {

tinygltf::Model new_model(const GltfOptions& options) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = options.generator;
  m.buffers.emplace_back();
  tinygltf::Sampler sampler;  // trilinear, clamped: the atlas gutters hold each tile's own edge texels
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  m.samplers.push_back(sampler);
  return m;
}

// An index accessor of `idx`, uint16 where every index fits (below 65535, which the spec leaves to
// primitive restart: half the bytes for every level and most LODs), else uint32; returns its index.
int add_indices(tinygltf::Model& m, const std::vector<std::uint32_t>& idx) {
  tinygltf::Accessor ia;
  if (std::all_of(idx.begin(), idx.end(), [](std::uint32_t i) { return i < 65535; })) {
    const std::vector<std::uint16_t> narrow(idx.begin(), idx.end());
    ia.bufferView = add_view(m, narrow.data(), narrow.size() * sizeof(std::uint16_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  } else {
    ia.bufferView = add_view(m, idx.data(), idx.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  }
  ia.count = idx.size();
  ia.type = TINYGLTF_TYPE_SCALAR;
  m.accessors.push_back(ia);
  return static_cast<int>(m.accessors.size() - 1);
}

// `mesh` as the model's only mesh, held by its only node, the default scene's one root; returns
// the node.
tinygltf::Node& add_single_node_scene(tinygltf::Model& m, tinygltf::Mesh mesh) {
  tinygltf::Node node;
  node.name = mesh.name;
  node.mesh = static_cast<int>(m.meshes.size());
  m.meshes.push_back(std::move(mesh));
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(static_cast<int>(m.nodes.size() - 1));
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return m.nodes.back();
}

// A level's textures, encoded side by side: one encoder a texture on each thread (ETC1S's
// codebook stages run on one thread whatever its job pool holds), the whole pool for a lone one.
// Each texture's bytes do not depend on the threads.
struct LevelImage {
  const std::vector<std::uint8_t>* rgba;
  int w, h;
  TextureClass cls;
};
std::vector<std::vector<std::uint8_t>> encoded_images(const std::vector<LevelImage>& images, const GltfOptions& options) {
  std::vector<std::vector<std::uint8_t>> out(images.size());
  GltfOptions each = options;
  if (images.size() > 1) each.threads = 1;
  std::vector<std::exception_ptr> failed(images.size());  // an encoder's error, thrown after the loop
#pragma omp parallel for schedule(dynamic) num_threads(std::max(1, std::min<int>(options.threads, static_cast<int>(images.size()))))
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(images.size()); ++i) {
    const auto k = static_cast<std::size_t>(i);
    try {
      out[k] = encoded_image(*images[k].rgba, images[k].w, images[k].h, images[k].cls, each);
    } catch (...) {
      failed[k] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  return out;
}

// A level's materials, one per atlas image (one draw call each in an engine); returns the first's
// index.
int add_level_materials(tinygltf::Model& m, const Atlas& atlas, const GltfOptions& options, const std::string& prefix,
                        TextureCost* cost) {
  const int first_material = static_cast<int>(m.materials.size());
  // 1. Every texture of the level, encoded (in the order they are added below). Normal maps are
  // stored at half the atlas's size, a quarter of its texels, in the same texture coordinates
  // (docs/textures.md): lighting varies more slowly over a quad than its colour and alpha edge do.
  std::vector<TextureImage> normals;
  for (std::size_t i = 0; i < atlas.normal_images.size(); ++i)
    normals.push_back(half_level(TextureImage{atlas.widths[i], atlas.heights[i], atlas.normal_images[i]}, {MipOptions::Kind::kNormal}));
  std::vector<LevelImage> images;
  for (std::size_t i = 0; i < atlas.images.size(); ++i) {
    const int w = atlas.widths[i], h = atlas.heights[i];
    images.push_back({&atlas.images[i], w, h, TextureClass::kColor});
    if (i < normals.size()) images.push_back({&normals[i].rgba, normals[i].width, normals[i].height, TextureClass::kNormal});
    if (i < atlas.orm_images.size()) images.push_back({&atlas.orm_images[i], w, h, TextureClass::kData});
    if (i < atlas.emissive_images.size()) images.push_back({&atlas.emissive_images[i], w, h, TextureClass::kEmissive});
  }
  const std::vector<std::vector<std::uint8_t>> encoded = encoded_images(images, options);
  std::size_t next = 0;
  const auto add = [&](const std::string& name) {
    const LevelImage& x = images[next];
    return add_encoded_texture(m, encoded[next++], x.w, x.h, name, options, cost);
  };
  // 2. The materials.
  for (std::size_t i = 0; i < atlas.images.size(); ++i) {
    tinygltf::Material mat;
    mat.name = prefix + "atlas_" + std::to_string(i);
    mat.pbrMetallicRoughness.baseColorTexture.index = add(mat.name + "_color");
    // The material channels (atlas.h LevelChannels): factors where constant (a rough dielectric
    // without emission where the input has none), textures in the atlas layout where they vary.
    const LevelChannels& ch = atlas.channels;
    mat.pbrMetallicRoughness.metallicFactor = canonical_double(ch.metallic);
    mat.pbrMetallicRoughness.roughnessFactor = canonical_double(ch.roughness);
    if (i < atlas.normal_images.size()) mat.normalTexture.index = add(mat.name + "_normal");
    if (i < atlas.orm_images.size()) {
      // One image: glTF's metallicRoughnessTexture reads G and B, occlusionTexture R.
      const int orm = add(mat.name + "_orm");
      mat.pbrMetallicRoughness.metallicRoughnessTexture.index = orm;
      if (ch.occlusion_texture) mat.occlusionTexture.index = orm;
    }
    mat.emissiveFactor = {canonical_double(ch.emissive[0]), canonical_double(ch.emissive[1]), canonical_double(ch.emissive[2])};
    if (i < atlas.emissive_images.size()) mat.emissiveTexture.index = add(mat.name + "_emissive");
    mat.alphaMode = options.alpha_mode;
    if (options.alpha_mode == "MASK") mat.alphaCutoff = options.alpha_cutoff;
    // Double-sided: seen from behind (an open surface's inside, a thin part's far side) a quad
    // still shows, lit with its flipped normal; culled, it leaves a hole (CGAL's lion, open at the
    // neck: 20% holes in three.js single-sided).
    mat.doubleSided = true;
    m.materials.push_back(mat);
  }
  const char* ext = options.textures == GltfOptions::Textures::kKtx2   ? kBasisuExtension
                    : options.textures == GltfOptions::Textures::kWebp ? kWebpExtension
                                                                       : nullptr;
  if (ext && !atlas.images.empty() && std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), ext) == m.extensionsUsed.end()) {
    m.extensionsUsed.push_back(ext);
    m.extensionsRequired.push_back(ext);
  }
  return first_material;
}

// The quads in the order the file holds them: by atlas image (one primitive each), then by index.
// The packer places tiles tallest first, so a level with several images interleaves them.
std::vector<std::size_t> quad_file_order(const ImpostorLevel& level) {
  std::vector<std::size_t> order(level.quads.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return level.atlas.tiles[a].atlas < level.atlas.tiles[b].atlas; });
  return order;
}

// The quads of atlas image `img` as one primitive (none when it has no quads).
void add_level_primitive(tinygltf::Model& m, tinygltf::Mesh& mesh, const ImpostorLevel& level, std::size_t img, int material) {
  const Atlas& atlas = level.atlas;
  // Normals, tangents and texture coordinates quantized (KHR_mesh_quantization): normal and tangent
  // as normalized bytes (within 0.5 degrees; a runtime takes the exact plane from the positions),
  // UVs as normalized shorts (1/16 texel in a 4096 atlas); 120 bytes a quad instead of
  // 216 with floats. TANGENT stays although a flat quad's derived frame would equal it: without it
  // the glTF-Validator warns that a runtime-generated tangent space may be non-portable.
  std::vector<float> pos;
  std::vector<std::int8_t> nrm, tan;
  std::vector<std::uint16_t> uv;
  std::vector<std::uint32_t> idx;
  for (std::size_t k = 0; k < level.quads.size(); ++k) {
    if (atlas.tiles[k].atlas != img) continue;
    const SupportRect& q = level.quads[k];
    const AtlasTile& t = atlas.tiles[k];
    const auto base = static_cast<std::uint32_t>(pos.size() / 3);
    // Corners counter-clockwise about the normal: (-u,-v), (+u,-v), (+u,+v), (-u,+v). The
    // texture's top row (v0) is the rectangle's +v side.
    const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
    for (int c = 0; c < 4; ++c) {
      const Vec3f p = q.center + q.axis_u * (su[c] * level.half_u[k]) + q.axis_v * (sv[c] * level.half_v[k]);
      pos.insert(pos.end(), {p.x, p.y, p.z});
      using gltf_component::snorm8;
      nrm.insert(nrm.end(), {snorm8(q.normal.x), snorm8(q.normal.y), snorm8(q.normal.z), 0});  // padded to 4 bytes
      tan.insert(tan.end(), {snorm8(q.axis_u.x), snorm8(q.axis_u.y), snorm8(q.axis_u.z), 127});  // bitangent = normal x tangent = axis_v
      uv.insert(uv.end(), {gltf_component::unorm16(su[c] < 0 ? t.u0 : t.u1), gltf_component::unorm16(sv[c] < 0 ? t.v1 : t.v0)});
    }
    idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  if (idx.empty()) return;
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = material;
  prim.attributes["POSITION"] = add_floats(m, pos, 3, TINYGLTF_TYPE_VEC3, true);
  const std::size_t vertices = pos.size() / 3;
  prim.attributes["NORMAL"] = add_normalized(m, nrm.data(), vertices, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, 4);
  prim.attributes["TANGENT"] = add_normalized(m, tan.data(), vertices, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, 4);
  prim.attributes["TEXCOORD_0"] = add_normalized(m, uv.data(), vertices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, 4);
  prim.indices = add_indices(m, idx);
  mesh.primitives.push_back(prim);
}

// Adds a level: its materials, its quads as one mesh and a node holding it; returns the node's
// index. `prefix` names the level's objects.
int add_level(tinygltf::Model& m, const ImpostorLevel& level, const GltfOptions& options, const std::string& prefix,
              TextureCost* cost) {
  const int first_material = add_level_materials(m, level.atlas, options, prefix, cost);
  if (!level.quads.empty()) {
    m.extensionsUsed.push_back(kQuantizationExtension);
    m.extensionsRequired.push_back(kQuantizationExtension);
  }
  tinygltf::Mesh mesh;
  mesh.name = "impostor_level_" + std::to_string(level.level);
  for (std::size_t img = 0; img < level.atlas.images.size(); ++img)
    add_level_primitive(m, mesh, level, img, first_material + static_cast<int>(img));
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = mesh.name;
  node.mesh = static_cast<int>(m.meshes.size() - 1);
  m.nodes.push_back(node);
  return static_cast<int>(m.nodes.size() - 1);
}

// The extension's object: per quad its domain and error, and the neighbour graph as compressed
// rows, quads in the file's order (quad_file_order), the four arrays as accessors of the file's
// buffer (in JSON they were ~12 bytes an entry, 55 KB of bunny00's 873-quad level). A quad's
// plane and atlas rectangle are in its vertices (positions, UVs) and its primitive's material, so
// the extension does not repeat them. An array with no entries is left out (an accessor counts
// at least one).
Value impostor_extension(tinygltf::Model& m, const ImpostorLevel& level) {
  const std::vector<std::size_t> order = quad_file_order(level);
  std::vector<std::uint32_t> rank(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) rank[order[i]] = static_cast<std::uint32_t>(i);
  std::vector<std::uint32_t> domain, offsets{0}, neighbors;
  std::vector<float> errors;
  std::vector<std::vector<std::uint32_t>> adj(level.quads.size());
  for (const auto& e : level.edges) adj[rank[e[0]]].push_back(rank[e[1]]), adj[rank[e[1]]].push_back(rank[e[0]]);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const SupportRect& q = level.quads[order[i]];
    domain.push_back(q.domain);
    errors.push_back(static_cast<float>(q.error));
    std::sort(adj[i].begin(), adj[i].end());
    neighbors.insert(neighbors.end(), adj[i].begin(), adj[i].end());
    offsets.push_back(static_cast<std::uint32_t>(neighbors.size()));
  }
  Value::Object ext{{"level", Value(static_cast<int>(level.level))},
                    {"quadCount", Value(static_cast<int>(level.quads.size()))},
                    {"blend", Value(std::string("additive_sorted_lock_by_depth"))},
                    {"alphaRef", Value(canonical_double(level.alpha_ref))},
                    {"neighborOffsets", Value(add_unsigned(m, offsets))}};
  if (level.alpha_exponent != 1) ext["alphaExponent"] = Value(canonical_double(level.alpha_exponent));
  if (!level.quads.empty()) {
    ext["domain"] = Value(add_unsigned(m, domain));
    ext["error"] = Value(add_floats(m, errors, 1, TINYGLTF_TYPE_SCALAR, false, 0));
  }
  if (!neighbors.empty()) ext["neighbors"] = Value(add_unsigned(m, neighbors));
  return Value(ext);
}

std::vector<std::uint8_t> write_glb(tinygltf::Model& m) {
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  writer.WriteGltfSceneToStream(&m, out, /*prettyPrint=*/false, /*writeBinary=*/true);
  const std::string s = out.str();
  return std::vector<std::uint8_t>(s.begin(), s.end());
}

}  // namespace glb_model

const char* textures_name(GltfOptions::Textures textures) {
  return textures == GltfOptions::Textures::kKtx2 ? "ktx2" : textures == GltfOptions::Textures::kWebp ? "webp" : "png";
}

GltfOptions::Textures parse_textures(const std::string& name) {
  if (name == "png") return GltfOptions::Textures::kPng;
  if (name == "ktx2") return GltfOptions::Textures::kKtx2;
  if (name == "webp") return GltfOptions::Textures::kWebp;
  throw std::invalid_argument("'" + name + "' is not a texture format (png, ktx2 or webp)");
}

std::vector<std::uint8_t> encode_glb(const ImpostorLevel& level, const GltfOptions& options, TextureCost* cost) {
  tinygltf::Model m = new_model(options);
  tinygltf::Scene scene;
  scene.nodes.push_back(add_level(m, level, options, "impostor_", cost));
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  m.extensions[kImpostorExtension] = impostor_extension(m, level);
  m.extensionsUsed.push_back(kImpostorExtension);
  return write_glb(m);
}

double point_switch_distance(const PointImpostorInfo& info) {
  const double z0 = info.reference_height / (2 * std::tan(0.5 * info.reference_fov_degrees * 3.14159265358979323846 / 180));
  return info.pixel * z0;
}

}  // namespace qf
