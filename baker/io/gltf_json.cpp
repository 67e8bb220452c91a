// glTF JSON checks and rewriting (gltf_json.h).
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

// tinygltf built without Draco (Debian's) refuses a compressed primitive's `indices` accessor, which
// has no bufferView by design. Such primitives get their triangles from the Draco stream, so the
// key is dropped from the JSON (of a .gltf, or of a .glb's JSON chunk) before tinygltf sees it.
std::vector<std::uint8_t> without_draco_indices(ByteView bytes, nlohmann::json j) {
  const bool binary = bytes.size() >= 20 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  std::uint32_t json_length = 0;
  if (binary) std::memcpy(&json_length, bytes.data() + 12, 4);
  const std::size_t json_start = binary ? 20 : 0;
  if (!j.contains("meshes") || !j["meshes"].is_array()) return {};
  for (nlohmann::json& mesh : j["meshes"])
    if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
      for (nlohmann::json& p : mesh["primitives"])
        if (p.is_object() && p.contains("extensions") && p["extensions"].is_object() &&
            p["extensions"].contains("KHR_draco_mesh_compression"))
          p.erase("indices");
  std::string json = j.dump();
  if (!binary) return std::vector<std::uint8_t>(json.begin(), json.end());
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const std::size_t rest = json_start + json_length;
  std::vector<std::uint8_t> out(bytes.data(), bytes.data() + 12);
  const auto put32 = [&out](std::uint32_t v) { out.insert(out.end(), reinterpret_cast<std::uint8_t*>(&v), reinterpret_cast<std::uint8_t*>(&v) + 4); };
  put32(static_cast<std::uint32_t>(json.size()));
  put32(0x4E4F534A);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  out.insert(out.end(), bytes.data() + rest, bytes.data() + bytes.size());
  const auto total = static_cast<std::uint32_t>(out.size());
  std::memcpy(out.data() + 8, &total, 4);
  return out;
}

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
