// One LOD file from finished .glb files (the recommended chain's: mesh LODs, impostor levels, the
// point impostor), laid out as encode_lod_glb lays out the impostor levels.
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
    throw std::invalid_argument("combine_lod_glb: a part does not parse: " + err);
  if (m.buffers.size() > 1 || !m.skins.empty() || !m.animations.empty() || !m.cameras.empty())
    throw std::invalid_argument("combine_lod_glb: a part with several buffers, skins, animations or cameras");
  for (const std::string& e : m.extensionsRequired)
    throw std::invalid_argument("combine_lod_glb: a part requires " + e);
  return m;
}

void shift(int& index, std::size_t base) {
  if (index >= 0) index += static_cast<int>(base);
}

// Appends part `p` to `m` (one buffer, every index shifted); returns the index of its scene's root
// node in `m`.
int append_part(tinygltf::Model& m, tinygltf::Model p) {
  const std::size_t views = m.bufferViews.size(), accessors = m.accessors.size(), images = m.images.size(),
                    samplers = m.samplers.size(), textures = m.textures.size(), materials = m.materials.size(),
                    meshes = m.meshes.size(), nodes = m.nodes.size();
  std::vector<unsigned char>& buffer = m.buffers[0].data;
  buffer.resize((buffer.size() + 3) / 4 * 4, 0);
  const std::size_t offset = buffer.size();
  if (!p.buffers.empty()) buffer.insert(buffer.end(), p.buffers[0].data.begin(), p.buffers[0].data.end());
  for (tinygltf::BufferView& v : p.bufferViews) v.buffer = 0, v.byteOffset += offset, m.bufferViews.push_back(v);
  for (tinygltf::Accessor& a : p.accessors) shift(a.bufferView, views), m.accessors.push_back(a);
  for (tinygltf::Image& i : p.images) shift(i.bufferView, views), m.images.push_back(i);
  for (tinygltf::Sampler& s : p.samplers) m.samplers.push_back(s);
  for (tinygltf::Texture& t : p.textures) shift(t.source, images), shift(t.sampler, samplers), m.textures.push_back(t);
  for (tinygltf::Material& x : p.materials) {
    shift(x.pbrMetallicRoughness.baseColorTexture.index, textures);
    shift(x.pbrMetallicRoughness.metallicRoughnessTexture.index, textures);
    shift(x.normalTexture.index, textures);
    shift(x.occlusionTexture.index, textures);
    shift(x.emissiveTexture.index, textures);
    m.materials.push_back(x);
  }
  for (tinygltf::Mesh& mesh : p.meshes) {
    for (tinygltf::Primitive& prim : mesh.primitives) {
      for (auto& [name, accessor] : prim.attributes) shift(accessor, accessors);
      shift(prim.indices, accessors);
      shift(prim.material, materials);
    }
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
  const int scene = p.defaultScene >= 0 ? p.defaultScene : 0;
  if (p.scenes.empty() || p.scenes[static_cast<std::size_t>(scene)].nodes.size() != 1)
    throw std::invalid_argument("combine_lod_glb: a part whose scene has not exactly one root node");
  return p.scenes[static_cast<std::size_t>(scene)].nodes[0] + static_cast<int>(nodes);
}

}  // namespace

std::vector<std::uint8_t> combine_lod_glb(const std::vector<const std::vector<std::uint8_t>*>& parts,
                                          const std::vector<double>& screen_coverage, const std::string& name) {
  if (parts.empty() || screen_coverage.size() != parts.size())
    throw std::invalid_argument("combine_lod_glb: one screen coverage per part, at least one part");
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "quasiflat";
  m.buffers.resize(1);
  std::vector<int> roots;
  for (const std::vector<std::uint8_t>* part : parts) roots.push_back(append_part(m, parse_glb(*part)));
  // Named NAME_LOD0..n, finest first: the suffix Unity, Unreal and Godot importers group as LODs.
  for (std::size_t i = 0; i < roots.size(); ++i) m.nodes[static_cast<std::size_t>(roots[i])].name = name + "_LOD" + std::to_string(i);
  // Only the first part's node is in the scene: engines without MSFT_lod draw it alone.
  tinygltf::Node& root = m.nodes[static_cast<std::size_t>(roots[0])];
  if (roots.size() > 1) {
    Value::Array ids, coverage;
    for (std::size_t i = 1; i < roots.size(); ++i) ids.push_back(Value(roots[i]));
    for (double c : screen_coverage) coverage.push_back(Value(c));
    root.extensions[kLodExtension] = Value(Value::Object{{"ids", Value(ids)}});
    root.extras = Value(Value::Object{{kScreenCoverageExtra, Value(coverage)}});
    m.extensionsUsed.push_back(kLodExtension);
  }
  tinygltf::Scene scene;
  scene.nodes.push_back(roots[0]);
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  writer.WriteGltfSceneToStream(&m, out, /*prettyPrint=*/false, /*writeBinary=*/true);
  const std::string s = out.str();
  return std::vector<std::uint8_t>(s.begin(), s.end());
}

}  // namespace qf
