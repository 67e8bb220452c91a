// Draco decoding for KHR_draco_mesh_compression input (see draco.h): the header's claimed counts
// read by hand, then Draco's decoder, its attributes converted to what glTF's accessors say.
#include "gltf/draco.h"

#include <draco/compression/decode.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

namespace qf {
namespace {

[[noreturn]] void broken(const std::string& what) { throw std::runtime_error(what); }

// A cursor over the stream, as Draco's DecoderBuffer reads it: little-endian fixed sizes and
// LEB128 varints of at most 32 bits.
struct Cursor {
  const std::uint8_t* bytes;
  std::size_t size, pos = 0;
  std::uint64_t fixed(int n) {
    if (size - pos < static_cast<std::size_t>(n)) broken("the Draco header is cut short at byte " + std::to_string(pos));
    std::uint64_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = v << 8 | bytes[pos + static_cast<std::size_t>(i)];
    pos += static_cast<std::size_t>(n);
    return v;
  }
  std::uint64_t varint() {
    std::uint64_t v = 0;
    for (int shift = 0;; shift += 7) {
      if (shift > 28) broken("a Draco varint longer than 32 bits at byte " + std::to_string(pos));
      const std::uint64_t b = fixed(1);
      v |= (b & 0x7F) << shift;
      if (!(b & 0x80)) break;
    }
    if (v > 0xFFFFFFFFu) broken("a Draco varint past 32 bits at byte " + std::to_string(pos));
    return v;
  }
  void skip(std::uint64_t n) {
    if (n > size - pos) broken("the Draco metadata reaches past the stream's end");
    pos += static_cast<std::size_t>(n);
  }
};

// One metadata block (metadata_decoder.cc): its entries (a name, a size, the bytes), then its
// sub-blocks, each a name and a block; walked with a counter, not recursion, so that a stream's
// nesting cannot decide the call stack's depth. Every step reads bytes, so a bogus count runs into
// the stream's end.
void skip_block(Cursor& c) {
  std::uint64_t pending = 1;
  for (bool root = true; pending > 0; root = false) {
    --pending;
    if (!root) c.skip(c.fixed(1));
    const std::uint64_t entries = c.varint();
    for (std::uint64_t i = 0; i < entries; ++i) c.skip(c.fixed(1)), c.skip(c.varint());
    pending += c.varint();
  }
}

// Draco's geometry metadata: per attribute an id and a block, then the geometry's own block.
void skip_metadata(Cursor& c) {
  const std::uint64_t attributes = c.varint();
  for (std::uint64_t i = 0; i < attributes; ++i) c.varint(), skip_block(c);
  skip_block(c);
}

}  // namespace

DracoCounts draco_peek_counts(const std::uint8_t* bytes, std::size_t size) {
  Cursor c{bytes, size};
  if (size < 11 || std::memcmp(bytes, "DRACO", 5) != 0) broken("not a Draco stream (no 'DRACO' header)");
  c.pos = 5;
  const auto major = c.fixed(1), minor = c.fixed(1), type = c.fixed(1), method = c.fixed(1), flags = c.fixed(2);
  const std::uint64_t version = major << 8 | minor;
  if (type != 1) broken("a Draco stream of a point cloud, not a triangle mesh");
  if (major < 1 || major > 2) broken("a Draco stream of version " + std::to_string(major) + "." + std::to_string(minor));
  if (version >= 0x0103 && (flags & 0x8000)) skip_metadata(c);
  const auto count = [&]() { return version < 0x0200 ? c.fixed(4) : c.varint(); };
  DracoCounts out;
  if (method == 0) {  // sequential: faces, then points
    out.faces = version < 0x0202 ? c.fixed(4) : c.varint();
    out.points = version < 0x0202 ? c.fixed(4) : c.varint();
  } else if (method == 1) {  // edgebreaker: traversal type, [new vertices], vertices, faces
    c.fixed(1);
    if (version < 0x0202) count();
    count();  // vertices of the connectivity; the points, after attribute seams, are at most 3 a face
    out.faces = count();
    out.points = out.faces * 3;
  } else {
    broken("a Draco stream of unknown method " + std::to_string(method));
  }
  return out;
}

namespace {

// The mesh in `bytes`; throws std::runtime_error when it does not decode.
std::unique_ptr<draco::Mesh> decode(const std::uint8_t* bytes, std::size_t size) {
  draco::DecoderBuffer buf;
  buf.Init(reinterpret_cast<const char*>(bytes), size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buf);
  if (!decoded.ok()) broken("the Draco stream does not decode (" + decoded.status().error_msg_string() + ")");
  return std::move(decoded).value();
}

// Every point's value of `a` as `components` values of T (Draco's ConvertValue: integers to
// floats scaled when the attribute is normalized, missing components 0).
template <class T>
std::vector<std::uint8_t> values_as(const draco::Mesh& d, const draco::PointAttribute& a, int components) {
  const std::size_t n = static_cast<std::size_t>(components) * sizeof(T);
  std::vector<std::uint8_t> out(static_cast<std::size_t>(d.num_points()) * n);
  std::vector<T> v(static_cast<std::size_t>(components));
  for (draco::PointIndex i(0); i < d.num_points(); ++i) {
    if (!a.ConvertValue<T>(a.mapped_index(i), static_cast<std::int8_t>(components), v.data()))
      broken("the Draco attribute " + std::to_string(a.unique_id()) + " does not convert to " + std::to_string(components) + " components");
    std::memcpy(out.data() + i.value() * n, v.data(), n);
  }
  return out;
}

DracoValues typed_values(const draco::Mesh& d, const draco::PointAttribute& a, const DracoRequest& r) {
  const bool floats = r.component_type == 5126 || a.data_type() == draco::DT_FLOAT32 || a.data_type() == draco::DT_FLOAT64;
  if (floats) return {5126, values_as<float>(d, a, r.components)};
  switch (r.component_type) {
    case 5120: return {r.component_type, values_as<std::int8_t>(d, a, r.components)};
    case 5121: return {r.component_type, values_as<std::uint8_t>(d, a, r.components)};
    case 5122: return {r.component_type, values_as<std::int16_t>(d, a, r.components)};
    case 5123: return {r.component_type, values_as<std::uint16_t>(d, a, r.components)};
    case 5125: return {r.component_type, values_as<std::uint32_t>(d, a, r.components)};
    default: broken("componentType " + std::to_string(r.component_type) + " is not a vertex attribute's");
  }
}

}  // namespace

DracoTypedMesh draco_decode_typed(const std::uint8_t* bytes, std::size_t size, const std::vector<DracoRequest>& wanted) {
  const std::unique_ptr<draco::Mesh> d = decode(bytes, size);
  DracoTypedMesh out;
  out.points = d->num_points();
  out.corners.reserve(static_cast<std::size_t>(d->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < d->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out.corners.push_back(d->face(f)[k].value());
  for (const DracoRequest& r : wanted) {
    const draco::PointAttribute* a = d->GetAttributeByUniqueId(static_cast<std::uint32_t>(r.id));
    if (!a) broken("the Draco stream has no attribute with id " + std::to_string(r.id));
    if (r.components < 1 || r.components > 4) broken("an attribute of " + std::to_string(r.components) + " components");
    out.attributes[r.id] = typed_values(*d, *a, r);
  }
  return out;
}

void draco_decode(const std::vector<std::uint8_t>& bytes, std::vector<float>& positions, std::vector<std::uint32_t>& corners) {
  const std::unique_ptr<draco::Mesh> d = decode(bytes.data(), bytes.size());
  const draco::PointAttribute* p = d->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (!p) broken("the Draco stream has no POSITION attribute");
  const std::vector<std::uint8_t> raw = values_as<float>(*d, *p, 3);
  positions.resize(raw.size() / sizeof(float));
  std::memcpy(positions.data(), raw.data(), raw.size());
  corners.clear();
  for (draco::FaceIndex f(0); f < d->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) corners.push_back(d->face(f)[k].value());
}

}  // namespace qf
