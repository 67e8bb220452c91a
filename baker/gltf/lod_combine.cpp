// One MSFT_lod file from finished .glb files: the impostor levels of --lod-file, or the
// recommended chain's files (mesh LODs, impostor levels, the point impostor); and one file of
// several parts drawn together (a scan's tiles, qf-bake join).
#include "gltf/glb.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "core/gltf_keys.h"

namespace qf {
namespace {

using tinygltf::Value;

// Images are kept as their encoded bytes (bufferView + mimeType): nothing to decode.
bool keep_image_bytes(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; }

tinygltf::Model parse_glb(const std::vector<std::uint8_t>& bytes) {
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  std::string err, warn;
  if (!loader.LoadBinaryFromMemory(&m, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size())))
    throw std::invalid_argument("a part does not parse: " + err);
  if (m.buffers.size() > 1 || !m.skins.empty() || !m.animations.empty() || !m.cameras.empty())
    throw std::invalid_argument("a part with several buffers, skins, animations or cameras");
  // Only what append_part remaps: extensions may hold indices it would leave pointing elsewhere.
  const auto copied = [](const std::string& e) { return e == kBasisuExtension || e == kWebpExtension || e == kQuantizationExtension; };
  for (const std::string& e : m.extensionsRequired)
    if (!copied(e)) throw std::invalid_argument("a part requires " + e);
  for (const std::string& e : m.extensionsUsed)
    if (e != kImpostorExtension && e != kPointExtension && !copied(e)) throw std::invalid_argument("a part uses " + e);
  for (const tinygltf::Accessor& a : m.accessors)
    if (a.sparse.isSparse) throw std::invalid_argument("a part with a sparse accessor");
  for (const tinygltf::Mesh& mesh : m.meshes)
    for (const tinygltf::Primitive& prim : mesh.primitives)
      if (!prim.targets.empty()) throw std::invalid_argument("a part with morph targets");
  const int scene = m.defaultScene >= 0 ? m.defaultScene : 0;
  if (static_cast<std::size_t>(scene) >= m.scenes.size() || m.scenes[static_cast<std::size_t>(scene)].nodes.size() != 1)
    throw std::invalid_argument("a part whose scene has not exactly one root node");
  return m;
}

void shift(int& index, std::size_t base) {
  if (index >= 0) index += static_cast<int>(base);
}

// Appends part `p` to `m` (one buffer, every index shifted; its meshes, materials, images and
// textures named PREFIX + their name, so that an importer keeps the parts' assets apart: two mesh
// LODs both named mesh_lod arrived in Blender as mesh_lod and mesh_lod.001); returns the index
// of its scene's root node in `m`. Only the accessors its meshes use and the bufferViews of those
// and of its images are copied: a level's QF_impostor_level arrays, accessors that the extension
// alone names, stay behind with it.
int append_part(tinygltf::Model& m, tinygltf::Model p, const std::string& prefix) {
  const std::size_t images = m.images.size(), samplers = m.samplers.size(), textures = m.textures.size(),
                    materials = m.materials.size(), meshes = m.meshes.size(), nodes = m.nodes.size();
  // 1. What the part's meshes and images use.
  std::vector<int> accessor_of(p.accessors.size(), -1), view_of(p.bufferViews.size(), -1);
  const auto use = [&](int accessor) {
    if (accessor < 0) return;
    accessor_of.at(static_cast<std::size_t>(accessor)) = 0;
    if (const int v = p.accessors[static_cast<std::size_t>(accessor)].bufferView; v >= 0) view_of.at(static_cast<std::size_t>(v)) = 0;
  };
  for (const tinygltf::Mesh& mesh : p.meshes)
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      for (const auto& [name, accessor] : prim.attributes) use(accessor);
      use(prim.indices);
    }
  for (const tinygltf::Image& i : p.images)
    if (i.bufferView >= 0) view_of.at(static_cast<std::size_t>(i.bufferView)) = 0;
  // 2. Those views' bytes, each 4-byte aligned, then the accessors over them.
  std::vector<unsigned char>& buffer = m.buffers[0].data;
  for (std::size_t k = 0; k < p.bufferViews.size(); ++k) {
    if (view_of[k] < 0) continue;
    tinygltf::BufferView v = p.bufferViews[k];
    buffer.resize((buffer.size() + 3) / 4 * 4, 0);
    if (p.buffers.empty() || v.byteOffset + v.byteLength > p.buffers[0].data.size()) throw std::invalid_argument("a part's bufferView reaches past its buffer");
    const auto* bytes = p.buffers[0].data.data() + v.byteOffset;
    v.buffer = 0;
    v.byteOffset = buffer.size();
    buffer.insert(buffer.end(), bytes, bytes + v.byteLength);
    view_of[k] = static_cast<int>(m.bufferViews.size());
    m.bufferViews.push_back(v);
  }
  const auto remap = [](int& index, const std::vector<int>& to) {
    if (index >= 0) index = to.at(static_cast<std::size_t>(index));
  };
  for (std::size_t k = 0; k < p.accessors.size(); ++k) {
    if (accessor_of[k] < 0) continue;
    tinygltf::Accessor a = p.accessors[k];
    remap(a.bufferView, view_of);
    accessor_of[k] = static_cast<int>(m.accessors.size());
    m.accessors.push_back(a);
  }
  for (tinygltf::Image& i : p.images) remap(i.bufferView, view_of), i.name = prefix + i.name, m.images.push_back(i);
  for (tinygltf::Sampler& s : p.samplers) m.samplers.push_back(s);
  for (tinygltf::Texture& t : p.textures) {
    shift(t.source, images), shift(t.sampler, samplers), t.name = prefix + t.name;
    // A KTX2 or WebP texture (KHR_texture_basisu, EXT_texture_webp) names its image in the extension.
    for (const char* name : {kBasisuExtension, kWebpExtension})
      if (auto ext = t.extensions.find(name); ext != t.extensions.end())
        ext->second = Value(Value::Object{{"source", Value(ext->second.Get("source").GetNumberAsInt() + static_cast<int>(images))}});
    m.textures.push_back(t);
  }
  for (tinygltf::Material& x : p.materials) {
    shift(x.pbrMetallicRoughness.baseColorTexture.index, textures);
    shift(x.pbrMetallicRoughness.metallicRoughnessTexture.index, textures);
    shift(x.normalTexture.index, textures);
    shift(x.occlusionTexture.index, textures);
    shift(x.emissiveTexture.index, textures);
    x.name = prefix + x.name;
    m.materials.push_back(x);
  }
  for (tinygltf::Mesh& mesh : p.meshes) {
    for (tinygltf::Primitive& prim : mesh.primitives) {
      for (auto& [name, accessor] : prim.attributes) remap(accessor, accessor_of);
      remap(prim.indices, accessor_of);
      shift(prim.material, materials);
    }
    mesh.name = prefix + mesh.name;
    m.meshes.push_back(mesh);
  }
  for (tinygltf::Node& n : p.nodes) {
    shift(n.mesh, meshes);
    for (int& c : n.children) shift(c, nodes);
    m.nodes.push_back(n);
  }
  for (const std::string& e : p.extensionsUsed)
    if (e != kImpostorExtension && e != kPointExtension && std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), e) == m.extensionsUsed.end())
      m.extensionsUsed.push_back(e);
  for (const std::string& e : p.extensionsRequired)
    if (std::find(m.extensionsRequired.begin(), m.extensionsRequired.end(), e) == m.extensionsRequired.end())
      m.extensionsRequired.push_back(e);
  return p.scenes[static_cast<std::size_t>(p.defaultScene >= 0 ? p.defaultScene : 0)].nodes[0] + static_cast<int>(nodes);
}

tinygltf::Model empty_model() {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "quasiflat";
  m.buffers.resize(1);
  return m;
}

std::vector<std::uint8_t> glb_bytes(tinygltf::Model& m, const char* who) {
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&m, out, /*prettyPrint=*/false, /*writeBinary=*/true))
    throw std::runtime_error(std::string(who) + ": tinygltf could not write the file");
  const std::string s = out.str();
  return std::vector<std::uint8_t>(s.begin(), s.end());
}

}  // namespace

std::size_t glb_image_bytes(const std::vector<std::uint8_t>& glb) {
  const tinygltf::Model m = parse_glb(glb);
  std::size_t bytes = 0;
  for (const tinygltf::Image& i : m.images)
    if (i.bufferView >= 0) bytes += m.bufferViews[static_cast<std::size_t>(i.bufferView)].byteLength;
  return bytes;
}

std::vector<std::uint8_t> join_glb(const std::vector<const std::vector<std::uint8_t>*>& parts, const std::string& name,
                                   const std::vector<std::string>& part_names) {
  if (parts.empty()) throw std::invalid_argument("join_glb: no part");
  if (!part_names.empty() && part_names.size() != parts.size()) throw std::invalid_argument("join_glb: not one name per part");
  tinygltf::Model m = empty_model();
  tinygltf::Node root;
  root.name = name;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string part = part_names.empty() ? name + "_" + std::to_string(i) : part_names[i];
    const int node = append_part(m, parse_glb(*parts[i]), part + "_");
    m.nodes[static_cast<std::size_t>(node)].name = part;
    root.children.push_back(node);
  }
  m.nodes.push_back(root);
  tinygltf::Scene scene;
  scene.nodes.push_back(static_cast<int>(m.nodes.size() - 1));
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return glb_bytes(m, "join_glb");
}

std::vector<std::uint8_t> combine_lod_glb(const std::vector<const std::vector<std::uint8_t>*>& parts,
                                          const std::vector<double>& screen_coverage, const std::string& name) {
  if (parts.empty() || screen_coverage.size() != parts.size())
    throw std::invalid_argument("combine_lod_glb: one screen coverage per part, at least one part");
  tinygltf::Model m = empty_model();
  std::vector<int> roots;
  for (std::size_t i = 0; i < parts.size(); ++i)
    roots.push_back(append_part(m, parse_glb(*parts[i]), name + "_LOD" + std::to_string(i) + "_"));
  // Named NAME_LOD0..n, finest first: the suffix Unity, Unreal and Godot importers group as LODs.
  for (std::size_t i = 0; i < roots.size(); ++i) m.nodes[static_cast<std::size_t>(roots[i])].name = name + "_LOD" + std::to_string(i);
  // Only the first part's node is in the scene: engines without MSFT_lod draw it alone.
  tinygltf::Node& root = m.nodes[static_cast<std::size_t>(roots[0])];
  if (roots.size() > 1) {
    Value::Array ids, coverage;
    for (std::size_t i = 1; i < roots.size(); ++i) ids.push_back(Value(roots[i]));
    for (double c : screen_coverage) coverage.push_back(Value(c));
    root.extensions[kLodExtension] = Value(Value::Object{{"ids", Value(ids)}});
    // Beside the part's own extras (a cluster LOD's cellWidth).
    Value::Object extras = root.extras.IsObject() ? root.extras.Get<Value::Object>() : Value::Object{};
    extras[kScreenCoverageExtra] = Value(coverage);
    root.extras = Value(extras);
    m.extensionsUsed.push_back(kLodExtension);
  }
  tinygltf::Scene scene;
  scene.nodes.push_back(roots[0]);
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return glb_bytes(m, "combine_lod_glb");
}

}  // namespace qf
