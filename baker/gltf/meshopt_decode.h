// EXT_meshopt_compression's bufferView decoding (meshoptimizer's decoder: vertex and index codecs,
// then the octahedral, quaternion or exponential filter), for the glTF readers of the baker and
// runtime_gl (gltf/compressed_gltf.cpp). Only meshoptimizer here, no glTF library.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace qf {

// One compressed bufferView as its EXT_meshopt_compression object describes it.
struct MeshoptView {
  std::string mode;             // "ATTRIBUTES", "TRIANGLES" or "INDICES"
  std::string filter = "NONE";  // "NONE", "OCTAHEDRAL", "QUATERNION" or "EXPONENTIAL" (ATTRIBUTES only)
  std::uint64_t count = 0;      // elements
  std::uint64_t stride = 0;     // bytes an element (byteStride)
};

// Bytes the decoded view takes: count * stride, 0 when that overflows 64 bits. For the memory
// check the caller makes before meshopt_decode allocates.
std::uint64_t meshopt_decoded_bytes(const MeshoptView& v);

// Throws std::runtime_error saying which rule `v` breaks (EXT_meshopt_compression's: ATTRIBUTES
// strides a multiple of 4 up to 256; TRIANGLES and INDICES strides 2 or 4, TRIANGLES counts a
// multiple of 3; a filter's stride; a known mode and filter). meshoptimizer asserts these, so they
// are checked before it is called.
void check_meshopt_view(const MeshoptView& v);

// The view decoded: count * stride bytes, little-endian as glTF stores them. Throws
// std::runtime_error when `v` breaks a rule (check_meshopt_view) or the `size` bytes at `data` do
// not decode (truncated or corrupt: meshoptimizer's decoders read within `size` and report it).
std::vector<std::uint8_t> meshopt_decode(const std::uint8_t* data, std::size_t size, const MeshoptView& v);

}  // namespace qf
