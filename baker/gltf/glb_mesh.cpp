// The mesh writers of glb.h: cluster LODs, point impostors, mesh LODs with the LOD material or
// their own textured materials (the impostor levels' writer is glb.cpp; the model-building steps
// both use are gltf/glb_model.h).
#include "gltf/glb.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "core/color.h"
#include "core/gltf_component.h"
#include "gltf/draco.h"
#include "gltf/glb_model.h"

namespace qf {

using namespace glb_model;
using tinygltf::Value;

namespace {

// COLOR_0 as normalized 16-bit linear RGBA (core/color.h; RGBA keeps elements 4-byte aligned).
std::vector<std::uint16_t> linear_rgba16(const std::vector<Rgb8>& colors) {
  std::vector<std::uint16_t> rgba;
  for (Rgb8 c : colors) rgba.insert(rgba.end(), {srgb_to_linear16(c.r), srgb_to_linear16(c.g), srgb_to_linear16(c.b), 65535});
  return rgba;
}

int add_colors(tinygltf::Model& m, const std::vector<Rgb8>& colors) {
  const std::vector<std::uint16_t> rgba = linear_rgba16(colors);
  tinygltf::Accessor a;
  a.bufferView = add_view(m, rgba.data(), rgba.size() * sizeof(std::uint16_t), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  a.normalized = true;
  a.count = colors.size();
  a.type = TINYGLTF_TYPE_VEC4;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

// An accessor with no bufferView (its data lives in a Draco stream).
int add_described(tinygltf::Model& m, int component, int type, std::size_t count, bool normalized = false) {
  tinygltf::Accessor a;
  a.componentType = component;
  a.type = type;
  a.count = count;
  a.normalized = normalized;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

// The triangles as a KHR_draco_mesh_compression primitive without fallback (gltf-notes.md 2.4).
tinygltf::Primitive draco_triangles(tinygltf::Model& m, const std::vector<float>& pos, const std::vector<float>& nrm,
                                    const std::vector<Rgb8>& col) {
  DracoInput in{pos, nrm, col.empty() ? std::vector<std::uint16_t>() : linear_rgba16(col)};
  const DracoOutput d = draco_compress(in);
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = 0;
  const int p = add_described(m, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, d.vertices);
  for (int k = 0; k < 3; ++k) {
    m.accessors[static_cast<std::size_t>(p)].minValues.push_back(canonical_double(static_cast<float>(d.min[static_cast<std::size_t>(k)])));
    m.accessors[static_cast<std::size_t>(p)].maxValues.push_back(canonical_double(static_cast<float>(d.max[static_cast<std::size_t>(k)])));
  }
  prim.attributes["POSITION"] = p;
  Value::Object ids{{"POSITION", Value(d.position_id)}};
  if (d.normal_id >= 0) {
    prim.attributes["NORMAL"] = add_described(m, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, d.vertices);
    ids["NORMAL"] = Value(d.normal_id);
  }
  if (d.color_id >= 0) {
    prim.attributes["COLOR_0"] = add_described(m, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, d.vertices, true);
    ids["COLOR_0"] = Value(d.color_id);
  }
  prim.indices = add_described(m, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, d.indices);
  const int view = add_view(m, d.bytes.data(), d.bytes.size(), 0);
  prim.extensions["KHR_draco_mesh_compression"] = Value(Value::Object{{"bufferView", Value(view)}, {"attributes", Value(ids)}});
  return prim;
}


// Mesh LODs, point impostors and simplified meshes share one material: a rough dielectric seen
// from both sides, white (times COLOR_0) for coloured inputs, else kUncolouredColor, so an engine
// draws them in the impostor levels' colour instead of the glTF default's metallic white (which
// three.js shows 3-60 dB off the reference, and ~48 grey levels off the impostor levels).
void add_lod_material(tinygltf::Model& m, const std::string& name, bool coloured) {
  tinygltf::Material mat;
  mat.name = name;
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 1.0;
  if (!coloured) {
    const Rgb8 c = kUncolouredColor;
    mat.pbrMetallicRoughness.baseColorFactor.clear();
    for (std::uint8_t v : {c.r, c.g, c.b}) mat.pbrMetallicRoughness.baseColorFactor.push_back(canonical_double(srgb_to_linear16(v) / 65535.0f));
    mat.pbrMetallicRoughness.baseColorFactor.push_back(1.0);
  }
  mat.doubleSided = true;
  m.materials.push_back(mat);
}

// A cluster LOD's triangles as corners (vertex indices) with smooth normals, area-weighted over
// the LOD's own triangles (xyz per corner).
void triangle_corners(const LodMesh& lod, std::vector<std::uint32_t>& corners, std::vector<float>& normals) {
  std::vector<Vec3f> vn(lod.positions.size());
  for (const Triangle& t : lod.triangles) {
    const Vec3f n = cross(lod.positions[t[1]] - lod.positions[t[0]], lod.positions[t[2]] - lod.positions[t[0]]);
    for (std::uint32_t v : t) vn[v] = vn[v] + n;
  }
  for (const Triangle& t : lod.triangles)
    for (std::uint32_t v : t) {
      corners.push_back(v);
      const Vec3f n = normalized(vn[v]);
      normals.insert(normals.end(), {n.x, n.y, n.z});
    }
}

}  // namespace

std::vector<std::uint8_t> encode_cluster_glb(const LodMesh& lod, const GltfOptions& options, bool draco) {
  tinygltf::Model m = new_model(options);
  m.samplers.clear();
  const bool coloured = lod.colors.size() == lod.positions.size() && !lod.colors.empty();
  add_lod_material(m, "cluster_lod", coloured);
  tinygltf::Mesh mesh;
  mesh.name = "cluster_lod";
  // Each primitive gets its own vertex arrays (unshared: simple, and a reader can take any alone).
  auto add_primitive = [&](int mode, const std::vector<std::uint32_t>& verts, const std::vector<float>* normals,
                           const std::vector<float>* thickness) {
    if (verts.empty()) return;
    std::vector<float> pos;
    std::vector<Rgb8> col;
    for (std::uint32_t v : verts) {
      pos.insert(pos.end(), {lod.positions[v].x, lod.positions[v].y, lod.positions[v].z});
      if (coloured) col.push_back(lod.colors[v]);
    }
    tinygltf::Primitive prim;
    prim.mode = mode;
    prim.material = 0;
    prim.attributes["POSITION"] = add_floats(m, pos, 3, TINYGLTF_TYPE_VEC3, true);
    if (normals) prim.attributes["NORMAL"] = add_floats(m, *normals, 3, TINYGLTF_TYPE_VEC3, false);
    if (coloured) prim.attributes["COLOR_0"] = add_colors(m, col);
    if (thickness) prim.attributes[kThicknessAttribute] = add_floats(m, *thickness, 1, TINYGLTF_TYPE_SCALAR, false);
    mesh.primitives.push_back(prim);
  };
  // Triangles: smooth normals, area-weighted over the LOD's own triangles.
  std::vector<std::uint32_t> tv;
  std::vector<float> tn;
  triangle_corners(lod, tv, tn);
  if (draco && !tv.empty()) {
    std::vector<float> pos;
    std::vector<Rgb8> col;
    for (std::uint32_t v : tv) {
      pos.insert(pos.end(), {lod.positions[v].x, lod.positions[v].y, lod.positions[v].z});
      if (coloured) col.push_back(lod.colors[v]);
    }
    mesh.primitives.push_back(draco_triangles(m, pos, tn, col));
  } else {
    add_primitive(TINYGLTF_MODE_TRIANGLES, tv, &tn, nullptr);
  }
  std::vector<std::uint32_t> ev;
  std::vector<float> et;
  for (std::size_t e = 0; e < lod.edges.size(); ++e)
    for (std::uint32_t v : lod.edges[e]) ev.push_back(v), et.push_back(lod.thickness[e]);
  add_primitive(TINYGLTF_MODE_LINE, ev, nullptr, &et);
  add_primitive(TINYGLTF_MODE_POINTS, lod.points, nullptr, nullptr);
  if (mesh.primitives.empty()) throw std::invalid_argument("encode_cluster_glb: an empty LOD");
  add_single_node_scene(m, mesh).extras = Value(Value::Object{{kCellWidthExtra, Value(canonical_double(lod.cell))}});
  if (draco && !tv.empty()) {  // no uncompressed fallback: readers without Draco must refuse the file
    m.extensionsUsed.push_back("KHR_draco_mesh_compression");
    m.extensionsRequired.push_back("KHR_draco_mesh_compression");
  }
  return write_glb(m);
}

std::vector<std::uint8_t> encode_point_glb(const PointSet& p, const PointImpostorInfo& info, const GltfOptions& options) {
  if (p.size() == 0) throw std::invalid_argument("encode_point_glb: no points");
  tinygltf::Model m = new_model(options);
  m.samplers.clear();  // no textures here
  std::vector<float> pos, nrm;
  for (Vec3f q : p.positions) pos.insert(pos.end(), {q.x, q.y, q.z});
  for (Vec3f q : p.normals) nrm.insert(nrm.end(), {q.x, q.y, q.z});
  add_lod_material(m, "point_impostor", p.has_colors());
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_POINTS;
  prim.material = 0;
  prim.attributes["POSITION"] = add_floats(m, pos, 3, TINYGLTF_TYPE_VEC3, true);
  if (!nrm.empty()) prim.attributes["NORMAL"] = add_floats(m, nrm, 3, TINYGLTF_TYPE_VEC3, false);
  if (p.has_colors()) {
    prim.attributes["COLOR_0"] = add_colors(m, p.colors);
  }
  tinygltf::Mesh mesh;
  mesh.name = "point_impostor";
  mesh.primitives.push_back(prim);
  add_single_node_scene(m, mesh);
  m.extensions[kPointExtension] = Value(Value::Object{
      {"pixelSize", Value(canonical_double(info.pixel))},
      {"pointCount", Value(static_cast<int>(p.size()))},
      {"seed", Value(static_cast<double>(info.seed))},
      {"switchDistance", Value(canonical_double(static_cast<float>(point_switch_distance(info))))},
      {"switchScreenHeight", Value(info.reference_height)},
      {"switchFovDegrees", Value(canonical_double(info.reference_fov_degrees))}});
  m.extensionsUsed.push_back(kPointExtension);
  return write_glb(m);
}

std::vector<std::uint8_t> encode_mesh_glb(const TriangleMesh& mesh, bool smooth_normals, const GltfOptions& options) {
  if (mesh.triangles.empty()) throw std::invalid_argument("encode_mesh_glb: a mesh without triangles");
  tinygltf::Model m = new_model(options);
  m.samplers.clear();
  const bool coloured = mesh.colors.size() == mesh.positions.size() && !mesh.colors.empty();
  add_lod_material(m, "mesh_lod", coloured);
  std::vector<float> pos;
  for (Vec3f q : mesh.positions) pos.insert(pos.end(), {q.x, q.y, q.z});
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = 0;
  prim.attributes["POSITION"] = add_floats(m, pos, 3, TINYGLTF_TYPE_VEC3, true);
  // The mesh's own normals where it has them (an input's hard edges stay hard), else smooth ones.
  const bool own_normals = mesh.normals.size() == mesh.positions.size();
  if (own_normals || smooth_normals) {
    std::vector<float> nrm;
    for (Vec3f n : own_normals ? mesh.normals : mesh.smooth_normals()) nrm.insert(nrm.end(), {n.x, n.y, n.z});
    prim.attributes["NORMAL"] = add_floats(m, nrm, 3, TINYGLTF_TYPE_VEC3, false);
  }
  if (coloured) prim.attributes["COLOR_0"] = add_colors(m, mesh.colors);
  std::vector<std::uint32_t> idx;
  for (const Triangle& t : mesh.triangles) idx.insert(idx.end(), t.begin(), t.end());
  prim.indices = add_indices(m, idx);
  tinygltf::Mesh gm;
  gm.name = "mesh_lod";
  gm.primitives.push_back(prim);
  add_single_node_scene(m, gm);
  return write_glb(m);
}

namespace {

// A mesh texture with a sampler of its own (its wraps); returns the texture's index, -1 for none.
// PNG, RGBA as the reader took it whatever `cls` (the bytes of every earlier bake); KTX2 when the
// options ask for it, through the impostor levels' route (its codec by class, the mip levels
// written in; a MASK material's colour keeps its coverage at the material's own cutoff). WebP is
// the impostor levels' alone: a mesh LOD stays PNG.
int add_mesh_texture(tinygltf::Model& m, const TriangleMesh& mesh, const TextureRef& r, const std::string& name, TextureClass cls,
                     const GltfOptions& options, TextureCost* cost) {
  if (r.image < 0) return -1;
  const TextureImage& t = mesh.textures[static_cast<std::size_t>(r.image)];
  const bool ktx2 = options.textures == GltfOptions::Textures::kKtx2;
  GltfOptions o = options;
  if (!ktx2) o.textures = GltfOptions::Textures::kPng, cls = TextureClass::kColor;
  const int texture = add_texture(m, t.rgba, t.width, t.height, name, cls, o, cost);
  const auto code = [](TextureWrap w) {
    return w == TextureWrap::kClampToEdge ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE
           : w == TextureWrap::kMirroredRepeat ? TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT : TINYGLTF_TEXTURE_WRAP_REPEAT;
  };
  m.samplers.push_back(new_model({}).samplers[0]);
  m.samplers.back().wrapS = code(r.wrap_s), m.samplers.back().wrapT = code(r.wrap_t);
  m.textures[static_cast<std::size_t>(texture)].sampler = static_cast<int>(m.samplers.size() - 1);
  return texture;
}

int add_surface_material(tinygltf::Model& m, const TriangleMesh& mesh, const SurfaceMaterial& s, GltfOptions options, TextureCost* cost) {
  // The material's own alpha test, not the impostor levels', decides how its colour's mips keep coverage.
  options.alpha_mode = s.alpha_mode == AlphaMode::kMask ? "MASK" : "OPAQUE";
  options.alpha_cutoff = s.alpha_cutoff;
  tinygltf::Material mat;
  mat.name = s.name;
  mat.pbrMetallicRoughness.baseColorFactor.assign(s.base_color.begin(), s.base_color.end());
  mat.pbrMetallicRoughness.metallicFactor = canonical_double(s.metallic);
  mat.pbrMetallicRoughness.roughnessFactor = canonical_double(s.roughness);
  mat.emissiveFactor = {canonical_double(s.emissive[0]), canonical_double(s.emissive[1]), canonical_double(s.emissive[2])};
  mat.alphaMode = s.alpha_mode == AlphaMode::kMask ? "MASK" : s.alpha_mode == AlphaMode::kBlend ? "BLEND" : "OPAQUE";
  if (s.alpha_mode == AlphaMode::kMask) mat.alphaCutoff = s.alpha_cutoff;
  mat.doubleSided = s.double_sided;
  mat.pbrMetallicRoughness.baseColorTexture.index =
      add_mesh_texture(m, mesh, {s.texture, s.wrap_s, s.wrap_t}, s.name, TextureClass::kColor, options, cost);
  mat.pbrMetallicRoughness.metallicRoughnessTexture.index =
      add_mesh_texture(m, mesh, s.metallic_roughness, s.name + "_mr", TextureClass::kData, options, cost);
  mat.emissiveTexture.index = add_mesh_texture(m, mesh, s.emissive_texture, s.name + "_emissive", TextureClass::kEmissive, options, cost);
  mat.occlusionTexture.index = add_mesh_texture(m, mesh, s.occlusion, s.name + "_occlusion", TextureClass::kData, options, cost);
  if (mat.occlusionTexture.index >= 0) mat.occlusionTexture.strength = s.occlusion_strength;
  m.materials.push_back(mat);
  return static_cast<int>(m.materials.size() - 1);
}
}  // namespace

std::vector<std::uint8_t> encode_textured_mesh_glb(const TriangleMesh& mesh, const GltfOptions& options, TextureCost* cost) {
  if (mesh.triangles.empty()) throw std::invalid_argument("encode_textured_mesh_glb: a mesh without triangles");
  tinygltf::Model m = new_model(options);
  m.samplers.clear();
  tinygltf::Mesh gm;
  gm.name = "asset";
  for (std::size_t mi = 0; mi < std::max<std::size_t>(mesh.materials.size(), 1); ++mi) {
    // 1. This material's corners as vertices: (position, uv) pairs in first-use order.
    std::map<std::tuple<std::uint32_t, float, float>, std::uint32_t> vertex_of;
    std::vector<float> pos, nrm, uv;
    std::vector<Rgb8> col;
    std::vector<std::uint32_t> idx;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (!mesh.triangle_materials.empty() && mesh.triangle_materials[t] != mi) continue;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.triangles[t][static_cast<std::size_t>(k)];
        const Vec2f c = mesh.corner_uvs.empty() ? Vec2f{} : mesh.corner_uvs[t][static_cast<std::size_t>(k)];
        const auto [it, fresh] = vertex_of.emplace(std::make_tuple(v, c.x, c.y), static_cast<std::uint32_t>(pos.size() / 3));
        if (fresh) {
          const Vec3f p = mesh.positions[v];
          pos.insert(pos.end(), {p.x, p.y, p.z});
          if (!mesh.normals.empty()) nrm.insert(nrm.end(), {mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z});
          if (!mesh.corner_uvs.empty()) uv.insert(uv.end(), {c.x, c.y});
          if (!mesh.colors.empty()) col.push_back(mesh.colors[v]);
        }
        idx.push_back(it->second);
      }
    }
    if (idx.empty()) continue;  // a material no triangle uses
    // 2. The primitive and its material.
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = mesh.materials.empty() ? -1 : add_surface_material(m, mesh, mesh.materials[mi], options, cost);
    prim.attributes["POSITION"] = add_floats(m, pos, 3, TINYGLTF_TYPE_VEC3, true);
    if (!nrm.empty()) prim.attributes["NORMAL"] = add_floats(m, nrm, 3, TINYGLTF_TYPE_VEC3, false);
    if (!uv.empty()) prim.attributes["TEXCOORD_0"] = add_floats(m, uv, 2, TINYGLTF_TYPE_VEC2, false);
    if (!col.empty()) prim.attributes["COLOR_0"] = add_colors(m, col);
    prim.indices = add_indices(m, idx);
    gm.primitives.push_back(prim);
  }
  if (options.textures == GltfOptions::Textures::kKtx2 && !m.images.empty()) {  // no PNG fallback, as the levels
    m.extensionsUsed.push_back(kBasisuExtension);
    m.extensionsRequired.push_back(kBasisuExtension);
  }
  add_single_node_scene(m, gm);
  return write_glb(m);
}

}  // namespace qf
