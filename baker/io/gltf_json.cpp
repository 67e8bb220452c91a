// glTF JSON checks (gltf_json.h).
#include "io/gltf_json.h"

#include <cstring>
#include <set>

#include "core/error.h"

namespace qf::io {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& code, const std::string& where, const std::string& what) {
  throw InputError("gltf." + code, path, where, what);
}

const char* json_kind(const nlohmann::json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return "an array";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  return "null";
}

std::string json_found(const nlohmann::json& v) {
  return v.is_number() ? v.dump() : json_kind(v);
}

void check_types(const nlohmann::json& j, const std::string& where, const std::string& path) {
  static const std::set<std::string> uints{"scene", "mesh", "skin", "camera", "indices", "material", "mode", "bufferView",
                                           "byteOffset", "byteLength", "byteStride", "componentType", "count", "buffer",
                                           "index", "texCoord", "sampler", "source", "wrapS", "wrapT", "magFilter",
                                           "minFilter", "target"};
  static const std::set<std::string> strings{"name", "uri", "mimeType", "type", "alphaMode", "version", "generator"};
  static const std::set<std::string> numbers{"alphaCutoff", "strength", "metallicFactor", "roughnessFactor"};
  static const std::set<std::string> objects{"asset", "attributes", "pbrMetallicRoughness", "baseColorTexture", "normalTexture",
                                             "occlusionTexture", "emissiveTexture", "metallicRoughnessTexture", "extensions",
                                             "KHR_texture_transform", "KHR_draco_mesh_compression", "sparse"};
  static const std::set<std::string> arrays{"scenes", "nodes", "meshes", "primitives", "accessors", "bufferViews", "buffers",
                                            "materials", "textures", "images", "samplers", "children", "targets", "matrix",
                                            "translation", "baseColorFactor", "emissiveFactor", "min", "max", "weights",
                                            "extensionsUsed", "extensionsRequired", "offset", "skins", "joints"};
  auto wrong = [&](const std::string& at, const char* expected, const nlohmann::json& v) {
    fail(path, "json_type", at, std::string("expected ") + expected + ", found " + json_found(v));
  };
  // Only what this reader reads: animations, cameras, skins and other extensions' contents are not.
  static const std::set<std::string> read_top{"asset", "scene", "scenes", "nodes", "meshes", "accessors", "bufferViews",
                                              "buffers", "materials", "textures", "images", "samplers",
                                              "extensionsUsed", "extensionsRequired"};
  const bool in_extensions = where.size() >= 10 && where.compare(where.size() - 10, 10, "extensions") == 0;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    const nlohmann::json& v = it.value();
    const std::string at = where.empty() ? key : where + "." + key;
    if (key == "extras" || (where.empty() && !read_top.count(key))) continue;
    if (in_extensions && key != "KHR_texture_transform" && key != "KHR_draco_mesh_compression") continue;
    if (uints.count(key) && !v.is_number_unsigned()) wrong(at, "a non-negative integer", v);
    if (strings.count(key) && !v.is_string()) wrong(at, "a string", v);
    if (numbers.count(key) && !v.is_number()) wrong(at, "a number", v);
    if (objects.count(key) && !v.is_object()) wrong(at, "an object", v);
    if (arrays.count(key) && !v.is_array()) wrong(at, "an array", v);
    // node scale and rotation are arrays, a texture transform's a number or an array of numbers.
    if ((key == "scale" || key == "rotation") && !v.is_number() && !v.is_array()) wrong(at, "a number or an array", v);
    if (v.is_object()) check_types(v, at, path);
    if (v.is_array())
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string ai = at + "[" + std::to_string(i) + "]";
        const bool index_list = key == "children" || key == "joints" || (key == "nodes" && where.rfind("scenes", 0) == 0);
        if (index_list && !v[i].is_number_unsigned()) wrong(ai, "a node index", v[i]);
        if (v[i].is_object()) check_types(v[i], ai, path);
      }
  }
}

}  // namespace

void check_gltf_json_types(const nlohmann::json& j, const std::string& path) { check_types(j, "", path); }

nlohmann::json gltf_json(ByteView bytes) {
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  std::uint32_t length = 0;
  if (binary && bytes.size() >= 20) std::memcpy(&length, bytes.data() + 12, 4);
  if (binary && (bytes.size() < 20 || length > bytes.size() - 20)) return nullptr;
  const char* text = reinterpret_cast<const char*>(bytes.data() + (binary ? 20 : 0));
  nlohmann::json j = nlohmann::json::parse(text, text + (binary ? length : bytes.size()), nullptr, false);
  return j.is_discarded() || !j.is_object() ? nlohmann::json() : j;
}

}  // namespace qf::io
