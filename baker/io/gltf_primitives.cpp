// glTF primitives read into plain arrays, every accessor checked against its buffer first
// (gltf_primitives.h).
#include "io/gltf_primitives.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <map>

#include "core/error.h"
#include "core/gltf_component.h"

namespace qf::io {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& code, const std::string& where, const std::string& what) {
  throw InputError("gltf." + code, path, where, what);
}

// ---- Accessors -------------------------------------------------------------------------------

// Reads accessors of one file, every read checked against its buffer view and buffer.
class Accessors {
 public:
  Accessors(const tinygltf::Model& m, const std::string& path) : m_(m), path_(path) {}

  // `components` floats per element; normalized integers become 0..1 / -1..1, other integers
  // their value (KHR_mesh_quantization). `allowed` is the set of component counts glTF allows.
  std::vector<float> floats(int index, int components, const std::string& where) const {
    const tinygltf::Accessor& a = accessor(index, where);
    if (tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)) != components)
      fail(path_, "accessor_type", where, "expected a " + std::to_string(components) + "-component accessor, found type " +
                                              std::to_string(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type))));
    const int csize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    if (csize <= 0) fail(path_, "accessor_type", where, "unknown componentType " + std::to_string(a.componentType));
    std::size_t stride = 0;
    // The count checked against the buffer before it sizes anything (a count of 2^62 asked for
    // 2^64 bytes: an internal error, not a refused file).
    const unsigned char* base = data(a, static_cast<std::size_t>(csize) * static_cast<std::size_t>(components), stride, where);
    std::vector<float> out(a.count * static_cast<std::size_t>(components));
    for (std::size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < components; ++c)
        out[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] =
            gltf_component::read(base + i * stride + static_cast<std::size_t>(c * csize), a.componentType, a.normalized);
    return out;
  }

  // Triangle-list or strip/fan vertex indices (unsigned byte, short or int), each < `vertices`.
  std::vector<std::uint32_t> indices(int index, std::size_t vertices, const std::string& where) const {
    const tinygltf::Accessor& a = accessor(index, where);
    const int ct = a.componentType;
    if (a.type != TINYGLTF_TYPE_SCALAR || (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                           ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
      fail(path_, "indices", where, "expected scalar unsigned byte, short or int indices");
    const std::size_t csize = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(ct)));
    std::size_t stride = 0;
    const unsigned char* base = data(a, csize, stride, where);
    std::vector<std::uint32_t> out(a.count);
    for (std::size_t i = 0; i < a.count; ++i) {
      const unsigned char* p = base + i * stride;
      std::uint32_t v = 0;
      if (csize == 1) v = *p;
      else if (csize == 2) { std::uint16_t s; std::memcpy(&s, p, 2); v = s; }
      else std::memcpy(&v, p, 4);
      if (v >= vertices)
        fail(path_, "index_range", where, "index " + std::to_string(v) + " out of range (" + std::to_string(vertices) + " vertices)");
      out[i] = v;
    }
    return out;
  }

  std::size_t count(int index, const std::string& where) const { return accessor(index, where).count; }

 private:
  const tinygltf::Accessor& accessor(int index, const std::string& where) const {
    if (index < 0 || static_cast<std::size_t>(index) >= m_.accessors.size())
      fail(path_, "accessor", where, "accessor " + std::to_string(index) + " does not exist (" +
                                         std::to_string(m_.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = m_.accessors[static_cast<std::size_t>(index)];
    if (a.sparse.isSparse) fail(path_, "sparse", where, "sparse accessors are not supported; store the values densely");
    if (a.bufferView < 0) fail(path_, "accessor", where, "accessor " + std::to_string(index) + " has no bufferView");
    return a;
  }

  // The first element's bytes and the stride, after checking that count elements of `elem` bytes
  // lie within the view and the view within its buffer.
  const unsigned char* data(const tinygltf::Accessor& a, std::size_t elem, std::size_t& stride, const std::string& where) const {
    if (static_cast<std::size_t>(a.bufferView) >= m_.bufferViews.size())
      fail(path_, "buffer_view", where, "bufferView " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& v = m_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= m_.buffers.size())
      fail(path_, "buffer", where, "buffer " + std::to_string(v.buffer) + " does not exist");
    const std::size_t buffer = m_.buffers[static_cast<std::size_t>(v.buffer)].data.size();
    if (v.byteOffset > buffer || v.byteLength > buffer - v.byteOffset)
      fail(path_, "buffer_view", where, "bufferView " + std::to_string(a.bufferView) + " (" + std::to_string(v.byteLength) +
                                            " bytes at " + std::to_string(v.byteOffset) + ") reaches past its buffer (" +
                                            std::to_string(buffer) + " bytes)");
    stride = v.byteStride ? v.byteStride : elem;
    const std::size_t need = a.count == 0 ? 0 : a.byteOffset + (a.count - 1) * stride + elem;
    if (a.count && (a.count - 1 > (SIZE_MAX - elem - a.byteOffset) / stride || need > v.byteLength))
      fail(path_, "accessor_bounds", where, "the accessor (" + std::to_string(a.count) + " elements) reaches past its bufferView (" +
                                                std::to_string(v.byteLength) + " bytes)");
    return m_.buffers[static_cast<std::size_t>(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
  }

  const tinygltf::Model& m_;
  const std::string& path_;
};


// ---- Primitives ------------------------------------------------------------------------------


// Triangle corners from the primitive's index list (or 0..n-1) by its mode; -1 for modes that
// have no triangles (points, lines).
bool triangle_corners(int mode, const std::vector<std::uint32_t>& idx, std::vector<std::uint32_t>& out) {
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (std::size_t i = 0; i + 2 < idx.size(); i += 3) out.insert(out.end(), {idx[i], idx[i + 1], idx[i + 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    // Every other triangle of a strip turns the other way; swapping its first two corners keeps the
    // winding of the first.
    for (std::size_t i = 0; i + 2 < idx.size(); ++i)
      if (i % 2 == 0) out.insert(out.end(), {idx[i], idx[i + 1], idx[i + 2]});
      else out.insert(out.end(), {idx[i + 1], idx[i], idx[i + 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 1; i + 1 < idx.size(); ++i) out.insert(out.end(), {idx[0], idx[i], idx[i + 1]});
  } else {
    return false;
  }
  return true;
}

// The attribute accessor `name` of a primitive, or -1.
int attribute(const tinygltf::Primitive& p, const std::string& name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

PrimitiveData read_primitive_impl(const tinygltf::Model& m, const Accessors& read, const tinygltf::Primitive& p, int uv_set,
                             const std::string& path, const std::string& where) {
  PrimitiveData out;
  const int pos = attribute(p, "POSITION");
  if (pos < 0) fail(path, "no_position", where + ".attributes", "has no POSITION attribute");
  out.positions = read.floats(pos, 3, where + ".attributes.POSITION");
  const std::size_t n = out.positions.size() / 3;
  auto same_count = [&](int index, const std::string& name) {
    if (read.count(index, where + ".attributes." + name) != n)
      fail(path, "attribute_count", where + ".attributes." + name,
           "has " + std::to_string(read.count(index, where + ".attributes." + name)) + " elements, POSITION has " + std::to_string(n));
  };
  if (const int a = attribute(p, "NORMAL"); a >= 0) same_count(a, "NORMAL"), out.normals = read.floats(a, 3, where + ".attributes.NORMAL");
  if (const int a = attribute(p, "COLOR_0"); a >= 0) {
    same_count(a, "COLOR_0");
    const std::size_t k = read.count(a, where + ".attributes.COLOR_0");
    const int comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(m.accessors[static_cast<std::size_t>(a)].type));
    const std::vector<float> c = read.floats(a, comps == 3 ? 3 : 4, where + ".attributes.COLOR_0");
    out.colors.resize(k * 4, 1.0f);
    for (std::size_t i = 0; i < k; ++i)
      for (int j = 0; j < (comps == 3 ? 3 : 4); ++j) out.colors[i * 4 + static_cast<std::size_t>(j)] = c[i * static_cast<std::size_t>(comps == 3 ? 3 : 4) + static_cast<std::size_t>(j)];
  }
  const std::string uv_name = "TEXCOORD_" + std::to_string(uv_set);
  if (const int a = attribute(p, uv_name); a >= 0) same_count(a, uv_name), out.uvs = read.floats(a, 2, where + ".attributes." + uv_name);
  std::vector<std::uint32_t> idx;
  if (p.indices >= 0) {
    idx = read.indices(p.indices, n, where + ".indices");
  } else {
    idx.resize(n);
    for (std::size_t i = 0; i < n; ++i) idx[i] = static_cast<std::uint32_t>(i);
  }
  triangle_corners(p.mode, idx, out.corners);
  return out;
}

}  // namespace

namespace {

// A varUI32 of the Draco bitstream (LEB128, at most 5 bytes); false past the end.
bool draco_varint(const std::uint8_t* b, std::size_t size, std::size_t& at, std::uint64_t& out) {
  out = 0;
  for (int shift = 0; shift < 35 && at < size; shift += 7) {
    const std::uint8_t byte = b[at++];
    out |= static_cast<std::uint64_t>(byte & 0x7F) << shift;
    if (!(byte & 0x80)) return true;
  }
  return false;
}

}  // namespace

double draco_decoding_bytes(const tinygltf::Model& m, const tinygltf::Primitive& p) {
  const auto ext = p.extensions.find("KHR_draco_mesh_compression");
  if (ext == p.extensions.end() || !ext->second.Has("bufferView") || !ext->second.Get("bufferView").IsInt()) return 0;
  const int view = ext->second.Get("bufferView").GetNumberAsInt();
  if (view < 0 || static_cast<std::size_t>(view) >= m.bufferViews.size()) return 0;
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(view)];
  if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= m.buffers.size()) return 0;
  const std::vector<unsigned char>& buffer = m.buffers[static_cast<std::size_t>(v.buffer)].data;
  if (v.byteOffset > buffer.size() || v.byteLength > buffer.size() - v.byteOffset) return 0;
  const std::uint8_t* b = buffer.data() + v.byteOffset;
  const std::size_t size = v.byteLength;
  // The header (Draco spec 3.2): "DRACO", version 2.2, a triangular mesh (type 1), its method
  // (0 sequential, 1 edgebreaker), flags (bit 15: metadata, which comes before the counts).
  if (size < 11 || std::memcmp(b, "DRACO", 5) != 0 || b[5] != 2 || b[6] != 2 || b[7] != 1 || (b[10] & 0x80)) return 0;
  std::size_t at = 11;
  std::uint64_t faces = 0, points = 0;
  if (b[8] == 0) {  // sequential: num_faces, num_points
    if (!draco_varint(b, size, at, faces) || !draco_varint(b, size, at, points)) return 0;
  } else if (b[8] == 1) {  // edgebreaker: traversal type, num_encoded_vertices, num_faces
    ++at;
    if (!draco_varint(b, size, at, points) || !draco_varint(b, size, at, faces)) return 0;
  } else {
    return 0;
  }
  // Per face: Draco's faces and corner table (opposite and vertex of each corner: 36 bytes) and
  // the corners handed over (12), with vectors' slack; per point: the attributes as Draco holds
  // them and as floats handed over (48 bytes each way) and its corner maps.
  constexpr double kFaceBytes = 64, kPointBytes = 128;
  return static_cast<double>(faces) * kFaceBytes + static_cast<double>(points) * kPointBytes;
}

PrimitiveData read_primitive(const tinygltf::Model& m, const tinygltf::Primitive& p, int uv_set, const std::string& path,
                             const std::string& where) {
  const Accessors read(m, path);
  return read_primitive_impl(m, read, p, uv_set, path, where);
}

}  // namespace qf::io
