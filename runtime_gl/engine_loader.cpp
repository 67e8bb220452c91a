// A glTF file as a standard engine sees it (engine_scene.h): node transforms composed, materials
// with the spec's defaults, vertex attributes in any type glTF allows for them.
#include <array>
#include <cmath>
#include <cstring>

#include "core/color.h"
#include "runtime_gl/gltf_read.h"

namespace qf::render {
namespace {

using namespace gltf;

// A vertex attribute as floats, `components` per vertex: FLOAT, or integers as glTF 2.0 3.7.2.1
// (normalized colours and texture coordinates) and KHR_mesh_quantization allow them (AccessorReader
// reads both). VEC3 colours get alpha 1 when `components` is 4.
std::vector<float> attribute_floats(const AccessorReader& read, int index, int components) {
  const tinygltf::Accessor& a = read.accessor(index);
  if (!(components == 4 && tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)) == 3))
    return read.floats(index, components);
  const std::vector<float> rgb = read.floats(index, 3);
  std::vector<float> out;
  out.reserve(rgb.size() / 3 * 4);
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) out.insert(out.end(), {rgb[i], rgb[i + 1], rgb[i + 2], 1.0f});
  return out;
}

Mat4d multiply(const Mat4d& a, const Mat4d& b) {
  Mat4d r{};
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr)
      for (int k = 0; k < 4; ++k) r[static_cast<std::size_t>(c * 4 + rr)] += a[static_cast<std::size_t>(k * 4 + rr)] * b[static_cast<std::size_t>(c * 4 + k)];
  return r;
}

// A node's local transform: its matrix, else T * R * S (glTF 2.0 3.5.3).
Mat4d local_transform(const tinygltf::Node& n) {
  Mat4d m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (n.matrix.size() == 16) {
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    return m;
  }
  const double x = n.rotation.size() == 4 ? n.rotation[0] : 0, y = n.rotation.size() == 4 ? n.rotation[1] : 0,
               z = n.rotation.size() == 4 ? n.rotation[2] : 0, w = n.rotation.size() == 4 ? n.rotation[3] : 1;
  const double sx = n.scale.size() == 3 ? n.scale[0] : 1, sy = n.scale.size() == 3 ? n.scale[1] : 1, sz = n.scale.size() == 3 ? n.scale[2] : 1;
  const Mat4d r{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
                2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
                2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0,
                0, 0, 0, 1};
  for (int k = 0; k < 4; ++k) {
    m[static_cast<std::size_t>(k)] = r[static_cast<std::size_t>(k)] * sx;
    m[static_cast<std::size_t>(4 + k)] = r[static_cast<std::size_t>(4 + k)] * sy;
    m[static_cast<std::size_t>(8 + k)] = r[static_cast<std::size_t>(8 + k)] * sz;
  }
  if (n.translation.size() == 3) m[12] = n.translation[0], m[13] = n.translation[1], m[14] = n.translation[2];
  return m;
}

EngineMaterial engine_material(const tinygltf::Model& m, int index, int& uv_set) {
  EngineMaterial out;  // glTF's default material
  uv_set = 0;
  if (index < 0 || index >= static_cast<int>(m.materials.size())) return out;
  const tinygltf::Material& mat = m.materials[static_cast<std::size_t>(index)];
  const tinygltf::PbrMetallicRoughness& pbr = mat.pbrMetallicRoughness;
  for (std::size_t c = 0; c < 4 && c < pbr.baseColorFactor.size(); ++c) out.base_color[c] = static_cast<float>(pbr.baseColorFactor[c]);
  auto image_of = [&](int texture) {
    if (texture < 0 || texture >= static_cast<int>(m.textures.size())) return -1;
    const int src = texture_source(m.textures[static_cast<std::size_t>(texture)]);
    return src >= 0 && src < static_cast<int>(m.images.size()) ? src : -1;
  };
  auto wraps_of = [&](int texture, int& s, int& t) {
    if (texture < 0 || texture >= static_cast<int>(m.textures.size())) return;
    const int sampler = m.textures[static_cast<std::size_t>(texture)].sampler;
    if (sampler < 0 || sampler >= static_cast<int>(m.samplers.size())) return;
    s = m.samplers[static_cast<std::size_t>(sampler)].wrapS;
    t = m.samplers[static_cast<std::size_t>(sampler)].wrapT;
  };
  out.base_texture = image_of(pbr.baseColorTexture.index);
  if (out.base_texture >= 0) uv_set = pbr.baseColorTexture.texCoord;
  wraps_of(pbr.baseColorTexture.index, out.base_wrap_s, out.base_wrap_t);
  wraps_of(mat.normalTexture.index, out.normal_wrap_s, out.normal_wrap_t);
  // KHR_texture_transform of the base colour texture (three.js applies it): uv' = T R S uv.
  out.uv_transform = base_uv_transform(m, index, uv_set);
  out.metallic = static_cast<float>(pbr.metallicFactor);
  out.roughness = static_cast<float>(pbr.roughnessFactor);
  out.normal_texture = image_of(mat.normalTexture.index);
  out.normal_scale = static_cast<float>(mat.normalTexture.scale);
  // Metallic-roughness, occlusion and emission (glTF 2.0 3.9.2-3.9.5); their textures sample the
  // base colour's uvs (the files qf-render draws use one set).
  out.metal_rough_texture = image_of(pbr.metallicRoughnessTexture.index);
  wraps_of(pbr.metallicRoughnessTexture.index, out.metal_rough_wrap_s, out.metal_rough_wrap_t);
  out.occlusion_texture = image_of(mat.occlusionTexture.index);
  wraps_of(mat.occlusionTexture.index, out.occlusion_wrap_s, out.occlusion_wrap_t);
  out.occlusion_strength = static_cast<float>(mat.occlusionTexture.strength);
  for (std::size_t c = 0; c < 3 && c < mat.emissiveFactor.size(); ++c) out.emissive[c] = static_cast<float>(mat.emissiveFactor[c]);
  out.emissive_texture = image_of(mat.emissiveTexture.index);
  wraps_of(mat.emissiveTexture.index, out.emissive_wrap_s, out.emissive_wrap_t);
  if (out.base_texture < 0) {  // without a base colour texture, the first channel texture's set
    if (out.metal_rough_texture >= 0) uv_set = pbr.metallicRoughnessTexture.texCoord;
    else if (out.emissive_texture >= 0) uv_set = mat.emissiveTexture.texCoord;
    else if (out.occlusion_texture >= 0) uv_set = mat.occlusionTexture.texCoord;
  }
  out.alpha = mat.alphaMode == "MASK" ? EngineMaterial::Alpha::kMask : mat.alphaMode == "BLEND" ? EngineMaterial::Alpha::kBlend : EngineMaterial::Alpha::kOpaque;
  out.alpha_cutoff = static_cast<float>(mat.alphaCutoff);
  out.double_sided = mat.doubleSided;
  return out;
}

// KHR_texture_transform applied to uv pairs: u' = a u + b v + c, v' = d u + e v + f.
void transform_uvs(const std::array<float, 6>& k, std::vector<float>& uvs) {
  for (std::size_t v = 0; v + 1 < uvs.size(); v += 2) {
    const float u0 = uvs[v], v0 = uvs[v + 1];
    uvs[v] = k[0] * u0 + k[1] * v0 + k[2];
    uvs[v + 1] = k[3] * u0 + k[4] * v0 + k[5];
  }
}

// A strip's or fan's indices as a triangle list (every other strip triangle turned back to the
// first's winding).
std::vector<std::uint32_t> triangle_list(int mode, const std::vector<std::uint32_t>& idx) {
  std::vector<std::uint32_t> list;
  for (std::size_t i = 0; i + 2 < idx.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) list.insert(list.end(), {idx[0], idx[i + 1], idx[i + 2]});
    else if (i % 2 == 0) list.insert(list.end(), {idx[i], idx[i + 1], idx[i + 2]});
    else list.insert(list.end(), {idx[i + 1], idx[i], idx[i + 2]});
  }
  return list;
}

// One primitive of a mesh, placed by `world`.
EnginePrimitive engine_primitive(const AccessorReader& read, const tinygltf::Primitive& prim, const Mat4d& world) {
  EnginePrimitive p;
  if (prim.mode == TINYGLTF_MODE_LINE) p.mode = EnginePrimitive::Mode::kLines;
  else if (prim.mode == TINYGLTF_MODE_POINTS) p.mode = EnginePrimitive::Mode::kPoints;
  int uv_set = 0;
  p.material = engine_material(read.m, prim.material, uv_set);
  auto attribute = [&](const std::string& name, int components) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? std::vector<float>() : attribute_floats(read, it->second, components);
  };
  p.positions = attribute("POSITION", 3);
  const std::size_t n = p.positions.size() / 3;
  p.normals = attribute("NORMAL", 3);
  p.tangents = attribute("TANGENT", 4);
  p.uvs = attribute("TEXCOORD_" + std::to_string(uv_set), 2);
  p.colors = attribute("COLOR_0", 4);
  if ((!p.normals.empty() && p.normals.size() != n * 3) || (!p.tangents.empty() && p.tangents.size() != n * 4) ||
      (!p.uvs.empty() && p.uvs.size() != n * 2) || (!p.colors.empty() && p.colors.size() != n * 4))
    fail(read.path, "mesh", "a primitive's attributes differ in count from POSITION");
  transform_uvs(p.material.uv_transform, p.uvs);
  if (prim.indices >= 0) {
    p.indices = read.indices(prim.indices);
    for (std::uint32_t i : p.indices)
      if (i >= n) fail(read.path, "mesh", "index " + std::to_string(i) + " out of range (" + std::to_string(n) + " vertices)");
  } else {
    for (std::uint32_t i = 0; i < n; ++i) p.indices.push_back(i);
  }
  if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP || prim.mode == TINYGLTF_MODE_TRIANGLE_FAN)
    p.indices = triangle_list(prim.mode, p.indices);
  // World space: points by the matrix, normals by its inverse transpose (the cofactor matrix,
  // normalised), tangents by the matrix; a negative determinant mirrors, so flip the winding.
  const Mat4d& w = world;
  auto at = [&](int r, int c) { return w[static_cast<std::size_t>(c * 4 + r)]; };
  const double det = at(0, 0) * (at(1, 1) * at(2, 2) - at(1, 2) * at(2, 1)) - at(0, 1) * (at(1, 0) * at(2, 2) - at(1, 2) * at(2, 0)) +
                     at(0, 2) * (at(1, 0) * at(2, 1) - at(1, 1) * at(2, 0));
  for (std::size_t v = 0; v < n; ++v) {
    const double x = p.positions[v * 3], y = p.positions[v * 3 + 1], z = p.positions[v * 3 + 2];
    for (int r = 0; r < 3; ++r) p.positions[v * 3 + static_cast<std::size_t>(r)] = static_cast<float>(at(r, 0) * x + at(r, 1) * y + at(r, 2) * z + at(r, 3));
  }
  auto cof = [&](int r, int c) {  // cofactor of the 3x3 part
    const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
    return at(r1, c1) * at(r2, c2) - at(r1, c2) * at(r2, c1);
  };
  // Directions (xyz of every `stride` floats) through a 3x3 matrix m(r, c), renormalised.
  auto turn = [](std::vector<float>& d, std::size_t stride, auto&& m) {
    for (std::size_t v = 0; v + 2 < d.size(); v += stride) {
      const Vec3f q{d[v], d[v + 1], d[v + 2]};
      Vec3f t;
      for (int r = 0; r < 3; ++r) t[r] = static_cast<float>(m(r, 0) * q.x + m(r, 1) * q.y + m(r, 2) * q.z);
      t = normalized(t);
      std::copy_n(&t.x, 3, &d[v]);
    }
  };
  turn(p.normals, 3, cof);
  turn(p.tangents, 4, at);
  if (det < 0 && p.mode == EnginePrimitive::Mode::kTriangles)
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) std::swap(p.indices[t + 1], p.indices[t + 2]);
  return p;
}

}  // namespace

std::array<float, 6> base_uv_transform(const tinygltf::Model& m, int material, int& uv_set) {
  std::array<float, 6> out{1, 0, 0, 0, 1, 0};
  if (material < 0 || material >= static_cast<int>(m.materials.size())) return out;
  const tinygltf::TextureInfo& info = m.materials[static_cast<std::size_t>(material)].pbrMetallicRoughness.baseColorTexture;
  const auto tt = info.extensions.find("KHR_texture_transform");
  if (tt == info.extensions.end() || !tt->second.IsObject()) return out;
  const tinygltf::Value& e = tt->second;
  auto num = [](const tinygltf::Value& v, int i, double fallback) {
    return v.IsArray() && static_cast<std::size_t>(i) < v.ArrayLen() && v.Get(i).IsNumber() ? v.Get(i).GetNumberAsDouble() : fallback;
  };
  const double r = e.Get("rotation").IsNumber() ? e.Get("rotation").GetNumberAsDouble() : 0.0;
  const double sx = num(e.Get("scale"), 0, 1), sy = num(e.Get("scale"), 1, 1);
  out = {static_cast<float>(std::cos(r) * sx), static_cast<float>(std::sin(r) * sy), static_cast<float>(num(e.Get("offset"), 0, 0)),
         static_cast<float>(-std::sin(r) * sx), static_cast<float>(std::cos(r) * sy), static_cast<float>(num(e.Get("offset"), 1, 0))};
  if (e.Get("texCoord").IsInt()) uv_set = e.Get("texCoord").GetNumberAsInt();
  return out;
}

void transform_uv_pairs(const std::array<float, 6>& k, std::vector<float>& uvs) { transform_uvs(k, uvs); }

std::vector<Mat4d> mesh_transforms(const tinygltf::Model& m) {
  const Mat4d identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::vector<Mat4d> out(m.meshes.size(), identity);
  std::vector<char> placed(m.meshes.size(), 0), seen(m.nodes.size(), 0), child(m.nodes.size(), 0);
  for (const tinygltf::Node& n : m.nodes)
    for (int c : n.children)
      if (c >= 0 && c < static_cast<int>(m.nodes.size())) child[static_cast<std::size_t>(c)] = 1;
  std::vector<int> roots = scene_roots(m);
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (!child[i]) roots.push_back(static_cast<int>(i));
  // Depth first with a stack of our own; a node is entered once (a cycle or a shared child ends there).
  std::vector<std::pair<int, Mat4d>> stack;
  for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, identity});
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (node < 0 || node >= static_cast<int>(m.nodes.size()) || seen[static_cast<std::size_t>(node)]) continue;
    seen[static_cast<std::size_t>(node)] = 1;
    const tinygltf::Node& n = m.nodes[static_cast<std::size_t>(node)];
    const Mat4d world = multiply(parent, local_transform(n));
    if (n.mesh >= 0 && n.mesh < static_cast<int>(m.meshes.size()) && !placed[static_cast<std::size_t>(n.mesh)])
      placed[static_cast<std::size_t>(n.mesh)] = 1, out[static_cast<std::size_t>(n.mesh)] = world;
    for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, world});
  }
  return out;
}

bool is_identity(const Mat4d& w) {
  for (std::size_t i = 0; i < 16; ++i)
    if (w[i] != (i % 5 == 0 ? 1.0 : 0.0)) return false;
  return true;
}

void place_points(const Mat4d& w, std::vector<float>& xyz) {
  for (std::size_t v = 0; v + 2 < xyz.size(); v += 3) {
    const double x = xyz[v], y = xyz[v + 1], z = xyz[v + 2];
    for (std::size_t r = 0; r < 3; ++r) xyz[v + r] = static_cast<float>(w[r] * x + w[4 + r] * y + w[8 + r] * z + w[12 + r]);
  }
}

void place_directions(const Mat4d& w, std::vector<float>& xyz) {
  auto at = [&](int r, int c) { return w[static_cast<std::size_t>(c * 4 + r)]; };
  auto cof = [&](int r, int c) {
    const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
    return at(r1, c1) * at(r2, c2) - at(r1, c2) * at(r2, c1);
  };
  for (std::size_t v = 0; v + 2 < xyz.size(); v += 3) {
    Vec3f t;
    for (int r = 0; r < 3; ++r) t[r] = static_cast<float>(cof(r, 0) * xyz[v] + cof(r, 1) * xyz[v + 1] + cof(r, 2) * xyz[v + 2]);
    t = normalized(t);
    std::copy_n(&t.x, 3, &xyz[v]);
  }
}

std::vector<int> scene_roots(const tinygltf::Model& m) {
  const int scene = m.defaultScene >= 0 ? m.defaultScene : (m.scenes.empty() ? -1 : 0);
  if (scene >= 0 && scene < static_cast<int>(m.scenes.size())) return m.scenes[static_cast<std::size_t>(scene)].nodes;
  return {};
}

EngineScene engine_scene(const tinygltf::Model& m, const std::string& path, const std::vector<int>& roots) {
  EngineScene s;
  for (const tinygltf::Image& img : m.images) s.images.push_back(to_image(img, path));
  AccessorReader read{m, path};
  // Depth first (a node's primitives, then its children's in order) with a stack of our own: the
  // file's depth must not decide the call stack's. The nodes must form a tree (glTF 2.0, 3.5.3),
  // as the bake's reader requires: a node among its own ancestors is a cycle, and a node reached
  // twice is refused too, as it multiplies the primitives below it (nodes each naming the next
  // twice: 2^23 copies of a mesh from 2.5 KB, found by fuzz_glb, issue 50).
  std::vector<char> on_path(m.nodes.size(), 0), reached(m.nodes.size(), 0);
  const Mat4d identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  struct Step {
    int node;
    Mat4d parent;
    bool leave;  // the walk leaves `node`: no longer an ancestor
  };
  std::vector<Step> stack;
  for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, identity, false});
  while (!stack.empty()) {
    const Step step = stack.back();
    stack.pop_back();
    const int node = step.node;
    if (step.leave) {
      on_path[static_cast<std::size_t>(node)] = 0;
      continue;
    }
    if (node < 0 || node >= static_cast<int>(m.nodes.size())) fail(path, "nodes", "node " + std::to_string(node) + " does not exist");
    if (on_path[static_cast<std::size_t>(node)]) fail(path, "nodes", "nodes[" + std::to_string(node) + "] is its own ancestor (a cycle)");
    if (reached[static_cast<std::size_t>(node)])
      fail(path, "nodes", "nodes[" + std::to_string(node) + "] is reached twice (a child of two nodes, or listed twice); glTF nodes form a tree");
    on_path[static_cast<std::size_t>(node)] = reached[static_cast<std::size_t>(node)] = 1;
    const tinygltf::Node& n = m.nodes[static_cast<std::size_t>(node)];
    const Mat4d world = multiply(step.parent, local_transform(n));
    if (n.mesh >= 0 && n.mesh < static_cast<int>(m.meshes.size()))
      for (const tinygltf::Primitive& prim : m.meshes[static_cast<std::size_t>(n.mesh)].primitives)
        if (prim.mode == TINYGLTF_MODE_TRIANGLES || prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
            prim.mode == TINYGLTF_MODE_TRIANGLE_FAN || prim.mode == TINYGLTF_MODE_LINE || prim.mode == TINYGLTF_MODE_POINTS)
          s.primitives.push_back(engine_primitive(read, prim, world));
    stack.push_back({node, identity, true});
    for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, world, false});
  }
  for (const EnginePrimitive& p : s.primitives) {
    for (std::size_t v = 0; v + 2 < p.positions.size(); v += 3) s.bounds.add({p.positions[v], p.positions[v + 1], p.positions[v + 2]});
    for (int t : {p.material.base_texture, p.material.normal_texture, p.material.metal_rough_texture, p.material.occlusion_texture,
                  p.material.emissive_texture})
      if (t >= static_cast<int>(s.images.size())) fail(path, "image", "a material names a missing image");
  }
  return s;
}

}  // namespace qf::render
