// Compressed glTF input made plain (see compressed_gltf.h): meshopt views and Draco primitives.
#include "gltf/compressed_gltf.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <string_view>

#include "core/error.h"
#include "core/gltf_component.h"
#include "core/gltf_keys.h"
#include "core/input_limits.h"
#include "gltf/draco.h"
#include "gltf/meshopt_decode.h"

namespace qf::gltf_input {
namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kDraco = "KHR_draco_mesh_compression";

[[noreturn]] void fail(const DecodeContext& c, const char* code, const std::string& where, const std::string& what) {
  throw InputError(c.prefix + "." + code, c.path, where, what);
}

// ---- Before tinygltf --------------------------------------------------------------------------

// The JSON of a .gltf, or of a .glb's first chunk (null when it does not parse or is not an object).
nlohmann::json file_json(ByteView bytes, std::size_t& json_start, std::size_t& json_length) {
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  json_start = binary ? 20 : 0;
  json_length = bytes.size();
  if (binary) {
    std::uint32_t length = 0;
    if (bytes.size() < 20) return nullptr;
    std::memcpy(&length, bytes.data() + 12, 4);
    if (length > bytes.size() - 20) return nullptr;
    json_length = length;
  }
  const char* text = reinterpret_cast<const char*>(bytes.data() + json_start);
  nlohmann::json j = nlohmann::json::parse(text, text + json_length, nullptr, false);
  return j.is_discarded() || !j.is_object() ? nlohmann::json() : j;
}

// The key a Draco primitive's dropped `indices` is kept under, in its extension object: its count
// is what the stream must decode to (checked before Draco allocates for the stream's own claim).
constexpr const char* kKeptIndices = "qfIndicesAccessor";

// Drops a Draco primitive's `indices` (kept under kKeptIndices); returns whether anything changed.
bool drop_draco_indices(nlohmann::json& j) {
  bool changed = false;
  if (!j.contains("meshes") || !j["meshes"].is_array()) return false;
  for (nlohmann::json& mesh : j["meshes"])
    if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
      for (nlohmann::json& p : mesh["primitives"])
        if (p.is_object() && p.contains("extensions") && p["extensions"].is_object() && p["extensions"].contains(kDraco) &&
            p.contains("indices")) {
          if (p["extensions"][kDraco].is_object()) p["extensions"][kDraco][kKeptIndices] = p["indices"];
          p.erase("indices"), changed = true;
        }
  return changed;
}

// tinygltf holds an extension's integers as int (2^40 became 0): the numbers of the meshopt and
// Draco objects are checked here, exactly, to be integers tinygltf keeps as they are.
void check_numbers(const nlohmann::json& object, const std::string& where, const DecodeContext& c, const char* code) {
  for (const auto& [key, v] : object.items()) {
    if (key == kKeptIndices) continue;
    if (v.is_object()) check_numbers(v, where + "." + key, c, code);
    if (v.is_number() && !(v.is_number_unsigned() && v.get<std::uint64_t>() <= 0x7FFFFFFF))
      fail(c, code, where, key + " " + v.dump() + " is not an integer from 0 to 2147483647");
  }
}

void check_extension_numbers(const nlohmann::json& j, const DecodeContext& c) {
  if (j.contains("bufferViews") && j["bufferViews"].is_array())
    for (std::size_t i = 0; i < j["bufferViews"].size(); ++i) {
      const nlohmann::json& v = j["bufferViews"][i];
      if (v.is_object() && v.contains("extensions") && v["extensions"].is_object() && v["extensions"].contains(kMeshopt) &&
          v["extensions"][kMeshopt].is_object())
        check_numbers(v["extensions"][kMeshopt], "bufferViews[" + std::to_string(i) + "].extensions." + kMeshopt, c, "meshopt");
    }
  if (!j.contains("meshes") || !j["meshes"].is_array()) return;
  for (std::size_t i = 0; i < j["meshes"].size(); ++i) {
    const nlohmann::json& mesh = j["meshes"][i];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (std::size_t k = 0; k < mesh["primitives"].size(); ++k) {
      const nlohmann::json& p = mesh["primitives"][k];
      if (p.is_object() && p.contains("extensions") && p["extensions"].is_object() && p["extensions"].contains(kDraco) &&
          p["extensions"][kDraco].is_object())
        check_numbers(p["extensions"][kDraco], "meshes[" + std::to_string(i) + "].primitives[" + std::to_string(k) + "].extensions." + kDraco, c,
                      "draco");
    }
  }
}

// Makes every meshopt fallback buffer one byte of a data URI; returns whether anything changed.
bool shrink_fallback_buffers(nlohmann::json& j) {
  bool changed = false;
  if (!j.contains("buffers") || !j["buffers"].is_array()) return false;
  for (nlohmann::json& b : j["buffers"]) {
    if (!b.is_object() || !b.contains("extensions") || !b["extensions"].is_object()) continue;
    const nlohmann::json& e = b["extensions"].value(kMeshopt, nlohmann::json());
    if (!e.is_object() || e.value("fallback", false) != true) continue;
    b["byteLength"] = 1;
    b["uri"] = "data:application/octet-stream;base64,AA==";
    changed = true;
  }
  return changed;
}

}  // namespace

const std::vector<std::string>& decoded_extensions() {
  static const std::vector<std::string> names{kMeshopt, kDraco, kQuantizationExtension, kBasisuExtension, kWebpExtension};
  return names;
}

std::vector<std::uint8_t> prepared_for_tinygltf(ByteView bytes, const DecodeContext& c) {
  const std::string_view view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (view.find(kDraco) == std::string_view::npos && view.find(kMeshopt) == std::string_view::npos) return {};
  std::size_t json_start = 0, json_length = 0;
  nlohmann::json j = file_json(bytes, json_start, json_length);
  if (j.is_null()) return {};  // tinygltf says why
  check_extension_numbers(j, c);
  const bool draco = drop_draco_indices(j), meshopt = shrink_fallback_buffers(j);
  if (!draco && !meshopt) return {};
  std::string json = j.dump();
  if (json_start == 0) return std::vector<std::uint8_t>(json.begin(), json.end());
  // A .glb: the header, the new JSON chunk (padded with spaces to 4 bytes), the rest as it was.
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::vector<std::uint8_t> out(bytes.data(), bytes.data() + 12);
  const auto put32 = [&out](std::uint32_t v) { out.insert(out.end(), reinterpret_cast<std::uint8_t*>(&v), reinterpret_cast<std::uint8_t*>(&v) + 4); };
  put32(static_cast<std::uint32_t>(json.size()));
  put32(0x4E4F534A);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  out.insert(out.end(), bytes.data() + json_start + json_length, bytes.data() + bytes.size());
  const auto total = static_cast<std::uint32_t>(out.size());
  std::memcpy(out.data() + 8, &total, 4);
  return out;
}

namespace {

// ---- Reading the extensions' objects ----------------------------------------------------------

// A non-negative integer member of an extension object; `fallback` when absent (-1: required).
std::uint64_t member(const DecodeContext& c, const tinygltf::Value& e, const char* key, const std::string& where, double fallback = -1) {
  if (!e.Has(key)) {
    if (fallback < 0) fail(c, "extension", where, std::string("has no ") + key);
    return static_cast<std::uint64_t>(fallback);
  }
  const tinygltf::Value& v = e.Get(key);
  const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1;
  if (!(d >= 0 && d <= 9007199254740992.0) || d != static_cast<double>(static_cast<std::uint64_t>(d)))
    fail(c, "extension", where, std::string(key) + " is not a non-negative integer");
  return static_cast<std::uint64_t>(d);
}

std::string string_member(const tinygltf::Value& e, const char* key, const std::string& fallback) {
  return e.Has(key) && e.Get(key).IsString() ? e.Get(key).Get<std::string>() : fallback;
}

// `length` bytes at `offset` of buffer `buffer`, checked to lie within it.
const std::uint8_t* buffer_range(const tinygltf::Model& m, const DecodeContext& c, const char* code, const std::string& where,
                                 std::uint64_t buffer, std::uint64_t offset, std::uint64_t length) {
  if (buffer >= m.buffers.size()) fail(c, code, where, "names buffer " + std::to_string(buffer) + ", which does not exist");
  const std::vector<unsigned char>& data = m.buffers[static_cast<std::size_t>(buffer)].data;
  if (offset > data.size() || length > data.size() - offset)
    fail(c, code, where, "its " + std::to_string(length) + " bytes at " + std::to_string(offset) + " reach past buffer " +
                             std::to_string(buffer) + " (" + std::to_string(data.size()) + " bytes)");
  return data.data() + offset;
}

// A new buffer holding `bytes` and a view over all of it; the view's index.
int add_view(tinygltf::Model& m, std::vector<std::uint8_t>&& bytes) {
  tinygltf::Buffer b;
  b.data = std::move(bytes);
  tinygltf::BufferView v;
  v.buffer = static_cast<int>(m.buffers.size());
  v.byteOffset = 0;
  v.byteLength = b.data.size();
  m.buffers.push_back(std::move(b));
  m.bufferViews.push_back(v);
  return static_cast<int>(m.bufferViews.size() - 1);
}

// ---- EXT_meshopt_compression --------------------------------------------------------------------

struct MeshoptJob {
  std::size_t view;
  MeshoptView desc;
  std::uint64_t buffer, offset, length;
};

// Every compressed view of the file, its object read and its rules checked.
std::vector<MeshoptJob> meshopt_jobs(const tinygltf::Model& m, const DecodeContext& c) {
  std::vector<MeshoptJob> jobs;
  for (std::size_t i = 0; i < m.bufferViews.size(); ++i) {
    const auto it = m.bufferViews[i].extensions.find(kMeshopt);
    if (it == m.bufferViews[i].extensions.end()) continue;
    const std::string where = "bufferViews[" + std::to_string(i) + "].extensions." + kMeshopt;
    const tinygltf::Value& e = it->second;
    if (!e.IsObject()) fail(c, "meshopt", where, "is not an object");
    MeshoptJob job{i, {string_member(e, "mode", ""), string_member(e, "filter", "NONE"), member(c, e, "count", where), member(c, e, "byteStride", where)},
                   member(c, e, "buffer", where), member(c, e, "byteOffset", where, 0), member(c, e, "byteLength", where)};
    try {
      check_meshopt_view(job.desc);
    } catch (const std::exception& ex) {
      fail(c, "meshopt", where, ex.what());
    }
    // A codec's output per input byte is bounded (meshopt's vertex codec: a 2-bit header per 16
    // bytes at best, 64:1; its index codecs: at least a byte per triangle or index), so a stream
    // claiming more than 1024 times its bytes is refused before anything is sized by the claim.
    if (meshopt_decoded_bytes(job.desc) / 1024 > job.length + 64)
      fail(c, "meshopt", where, "a stream of " + std::to_string(job.length) + " bytes cannot hold count x byteStride = " +
                                     std::to_string(meshopt_decoded_bytes(job.desc)) + " bytes");
    if (m.bufferViews[i].byteLength > meshopt_decoded_bytes(job.desc))
      fail(c, "meshopt", where, "the bufferView's byteLength " + std::to_string(m.bufferViews[i].byteLength) +
                                     " is more than count x byteStride " + std::to_string(meshopt_decoded_bytes(job.desc)));
    jobs.push_back(job);
  }
  return jobs;
}

void decode_meshopt(tinygltf::Model& m, const DecodeContext& c) {
  const std::vector<MeshoptJob> jobs = meshopt_jobs(m, c);
  if (jobs.empty()) return;
  // 1. The decoded sizes, summed, against the memory limit before any is allocated.
  double need = 0;
  for (const MeshoptJob& j : jobs) need += static_cast<double>(meshopt_decoded_bytes(j.desc));
  check_memory_need(static_cast<std::uint64_t>(std::min(need, 1e19)), c.memory_limit, c.path, c.prefix + ".memory", "",
                    "decoding its " + std::to_string(jobs.size()) + " meshopt-compressed bufferViews");
  // 2. Each view into a buffer of its own (the source buffers stay as they are until all are read).
  for (const MeshoptJob& j : jobs) {
    const std::string where = "bufferViews[" + std::to_string(j.view) + "].extensions." + kMeshopt;
    const std::uint8_t* src = buffer_range(m, c, "meshopt", where, j.buffer, j.offset, j.length);
    std::vector<std::uint8_t> decoded;
    try {
      decoded = meshopt_decode(src, static_cast<std::size_t>(j.length), j.desc);
    } catch (const std::exception& ex) {
      fail(c, "meshopt", where, ex.what());
    }
    tinygltf::Buffer b;
    b.data = std::move(decoded);
    m.buffers.push_back(std::move(b));
    tinygltf::BufferView& v = m.bufferViews[j.view];
    v.buffer = static_cast<int>(m.buffers.size() - 1);
    v.byteOffset = 0;
    v.extensions.erase(kMeshopt);
  }
}

// ---- KHR_draco_mesh_compression -----------------------------------------------------------------

// Bytes Draco and the decoded arrays take for a stream claiming `faces` and `points`: Draco's
// corner table and traversal (about 32 bytes a corner), the corners (4) and each point's
// attributes (at most 4 floats in each of `attributes`, doubled for Draco's copy and ours).
double draco_bytes(const DracoCounts& n, std::size_t attributes) {
  return static_cast<double>(n.faces) * 3 * 36 + static_cast<double>(n.points) * static_cast<double>(attributes) * 32;
}

// One primitive's stream decoded into new accessors; its attributes and indices pointed at them.
void decode_draco_primitive(tinygltf::Model& m, tinygltf::Primitive& p, const DecodeContext& c, const std::string& where) {
  const tinygltf::Value& e = p.extensions.at(kDraco);
  if (!e.IsObject() || !e.Has("attributes") || !e.Get("attributes").IsObject()) fail(c, "draco", where, "has no attributes object");
  const std::uint64_t view = member(c, e, "bufferView", where);
  if (view >= m.bufferViews.size()) fail(c, "draco", where, "names bufferView " + std::to_string(view) + ", which does not exist");
  // Copied: new views are added below.
  const tinygltf::BufferView v = m.bufferViews[static_cast<std::size_t>(view)];
  const std::uint8_t* bytes = buffer_range(m, c, "draco", where, v.buffer < 0 ? UINT64_MAX : static_cast<std::uint64_t>(v.buffer), v.byteOffset,
                                           v.byteLength);
  // 1. The attributes asked for: the stream's id of each, in the type its accessor declares.
  const tinygltf::Value& ids = e.Get("attributes");
  std::vector<DracoRequest> wanted;
  std::vector<std::pair<std::string, int>> names;  // attribute name -> the original accessor
  for (const std::string& name : ids.Keys()) {
    const auto acc = p.attributes.find(name);
    if (acc == p.attributes.end() || acc->second < 0 || static_cast<std::size_t>(acc->second) >= m.accessors.size())
      fail(c, "draco", where, "compresses " + name + ", which the primitive has no accessor for");
    const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(acc->second)];
    const std::uint64_t id = member(c, ids, name.c_str(), where + ".attributes");
    wanted.push_back({static_cast<int>(std::min<std::uint64_t>(id, INT32_MAX)), tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)), a.componentType});
    names.push_back({name, acc->second});
  }
  // 2. The claimed counts against the memory limit, before Draco allocates for them.
  DracoCounts counts;
  try {
    counts = draco_peek_counts(bytes, v.byteLength);
  } catch (const std::exception& ex) {
    fail(c, "draco", where, ex.what());
  }
  // The counts glTF declares for the decoded data (KHR_draco_mesh_compression: the indices
  // accessor's count is the triangles' corners; a sequential stream's points are POSITION's count).
  if (e.Has(kKeptIndices)) {
    const std::uint64_t kept = member(c, e, kKeptIndices, where);
    if (kept < m.accessors.size() && m.accessors[static_cast<std::size_t>(kept)].count != counts.faces * 3)
      fail(c, "draco", where, "the stream claims " + std::to_string(counts.faces) + " triangles, its indices accessor " +
                                  std::to_string(m.accessors[static_cast<std::size_t>(kept)].count) + " corners");
  }
  check_memory_need(static_cast<std::uint64_t>(std::min(draco_bytes(counts, wanted.size()), 1e19)), c.memory_limit, c.path, c.prefix + ".memory", where,
                    "a Draco stream claiming " + std::to_string(counts.faces) + " triangles and up to " + std::to_string(counts.points) + " points");
  DracoTypedMesh d;
  try {
    d = draco_decode_typed(bytes, v.byteLength, wanted);
  } catch (const std::exception& ex) {
    fail(c, "draco", where, ex.what());
  }
  // 3. New accessors over new views; the primitive points at them.
  for (std::size_t k = 0; k < wanted.size(); ++k) {
    tinygltf::Accessor a = m.accessors[static_cast<std::size_t>(names[k].second)];
    DracoValues& values = d.attributes[wanted[k].id];
    if (values.component_type != a.componentType) a.normalized = false;  // floats now: the values are scaled already
    a.componentType = values.component_type;
    a.count = d.points;
    a.byteOffset = 0;
    a.sparse.isSparse = false;
    a.bufferView = add_view(m, std::move(values.bytes));
    m.accessors.push_back(std::move(a));
    p.attributes[names[k].first] = static_cast<int>(m.accessors.size() - 1);
  }
  for (std::uint32_t corner : d.corners)
    if (corner >= d.points) fail(c, "draco", where, "a decoded triangle names point " + std::to_string(corner) + " of " + std::to_string(d.points));
  tinygltf::Accessor idx;
  idx.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  idx.type = TINYGLTF_TYPE_SCALAR;
  idx.count = d.corners.size();
  std::vector<std::uint8_t> raw(d.corners.size() * 4);
  if (!raw.empty()) std::memcpy(raw.data(), d.corners.data(), raw.size());
  idx.bufferView = add_view(m, std::move(raw));
  m.accessors.push_back(std::move(idx));
  p.indices = static_cast<int>(m.accessors.size() - 1);
  p.mode = TINYGLTF_MODE_TRIANGLES;  // Draco's faces are a triangle list whatever the mode was
  p.extensions.erase(kDraco);
}

}  // namespace

void decode_compressed(tinygltf::Model& m, const DecodeContext& c) {
  decode_meshopt(m, c);
  for (std::size_t i = 0; i < m.meshes.size(); ++i)
    for (std::size_t k = 0; k < m.meshes[i].primitives.size(); ++k) {
      tinygltf::Primitive& p = m.meshes[i].primitives[k];
      if (p.extensions.count(kDraco))
        decode_draco_primitive(m, p, c, "meshes[" + std::to_string(i) + "].primitives[" + std::to_string(k) + "].extensions." + kDraco);
    }
}

int texture_image(const tinygltf::Texture& t) {
  for (const char* name : {kBasisuExtension, kWebpExtension}) {
    const auto ext = t.extensions.find(name);
    if (ext == t.extensions.end() || !ext->second.IsObject() || !ext->second.Has("source")) continue;
    const tinygltf::Value& s = ext->second.Get("source");
    const double d = s.IsNumber() ? s.GetNumberAsDouble() : -1;
    if (d >= 0 && d < 1e9 && d == static_cast<double>(static_cast<int>(d))) return static_cast<int>(d);
  }
  return t.source;
}

}  // namespace qf::gltf_input
