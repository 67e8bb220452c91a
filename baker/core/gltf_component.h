// One component of a glTF accessor as a float (glTF 2.0 3.6.1: normalized integers map to [0, 1]
// or [-1, 1]; KHR_mesh_quantization allows them, and plain integers, for positions, normals,
// tangents and texture coordinates). Shared by the baker's glTF reader (io/gltf_primitives.cpp)
// and the runtime's (runtime_gl/gltf_read.h). Header only: the renderer includes it without
// linking the baker; the component types are the spec's numbers, so no glTF library is needed.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstring>

namespace qf::gltf_component {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;

// Bytes of one component of `type`; 0 for a type no vertex attribute uses.
inline int size_of(int type) {
  switch (type) {
    case kByte: case kUnsignedByte: return 1;
    case kShort: case kUnsignedShort: return 2;
    case kUnsignedInt: case kFloat: return 4;
    default: return 0;
  }
}

// The component at `p` (little-endian, as glTF stores it) of `type`, `normalized` as the accessor says.
inline float read(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case kFloat: { float f; std::memcpy(&f, p, 4); return f; }
    case kUnsignedByte: return normalized ? *p / 255.0f : *p;
    case kByte: { const auto s = static_cast<std::int8_t>(*p); return normalized ? std::max(s / 127.0f, -1.0f) : s; }
    case kUnsignedShort: { std::uint16_t s; std::memcpy(&s, p, 2); return normalized ? s / 65535.0f : s; }
    case kShort: { std::int16_t s; std::memcpy(&s, p, 2); return normalized ? std::max(s / 32767.0f, -1.0f) : s; }
    case kUnsignedInt: { std::uint32_t s; std::memcpy(&s, p, 4); return static_cast<float>(s); }
    default: return 0;
  }
}

// The normalized signed byte nearest to `x` in [-1, 1] (the writer's side of read).
inline std::int8_t snorm8(float x) { return static_cast<std::int8_t>(std::lround(std::clamp(x, -1.0f, 1.0f) * 127.0f)); }
// The normalized unsigned short nearest to `x` in [0, 1].
inline std::uint16_t unorm16(float x) { return static_cast<std::uint16_t>(std::lround(std::clamp(x, 0.0f, 1.0f) * 65535.0f)); }

}  // namespace qf::gltf_component
