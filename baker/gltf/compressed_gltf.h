// Compressed glTF input made plain for the three readers (the baker's io/gltf_read.cpp, runtime_gl's
// loader, qf-diff through it): EXT_meshopt_compression's bufferViews and KHR_draco_mesh_compression's
// primitives decoded into ordinary buffers, views and accessors, so that everything after reads
// them as it reads an uncompressed file. KHR_mesh_quantization needs no decoding (the accessor
// readers take its integer types, core/gltf_component.h); KTX2 and WebP images are
// gltf/image_decode.h. The codecs: meshoptimizer (gltf/meshopt_decode.h) and Draco (qf_draco).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/file_io.h"

namespace tinygltf {
class Model;
struct Texture;
}  // namespace tinygltf

namespace qf::gltf_input {

// The extensions the readers decode, as a file's extensionsRequired names them.
const std::vector<std::string>& decoded_extensions();

// What errors name: InputError(prefix + ".meshopt" / ".draco" / ".memory", path, where, what).
struct DecodeContext {
  std::string path;
  std::string prefix;            // "gltf" (baker) or "render.gltf" (runtime)
  std::size_t memory_limit = 0;  // as core/input_limits.h memory_limit takes it (0: memory available)
};

// The bytes of a .gltf or .glb rewritten where tinygltf 2.7 (Debian's, built without Draco) would
// refuse them, or empty when there is nothing to rewrite: a Draco primitive's `indices` (an accessor
// without a bufferView, by design) is dropped, its triangles come from the stream (the accessor's
// index is kept in the extension object, to check the stream's claimed count); a meshopt fallback
// buffer (EXT_meshopt_compression "fallback": no data, or data nobody needs) becomes one byte, so
// that tinygltf neither fails on it ("Invalid byteLength") nor reads the BIN chunk into it.
// The compressed objects' numbers are checked first (tinygltf keeps an extension's integers as int:
// a count of 2^40 became 0): InputError when one is not an integer from 0 to 2^31 - 1. Call it
// after the JSON's depth is checked (core/input_limits.h), before tinygltf parses.
std::vector<std::uint8_t> prepared_for_tinygltf(ByteView bytes, const DecodeContext& c);

// Decodes, in `m` as tinygltf parsed it from prepared_for_tinygltf's bytes: every meshopt-compressed
// bufferView into a buffer of its own (count x byteStride bytes), then every Draco primitive into
// new accessors (its attributes in the types the accessors declare, floats where Draco holds floats;
// UNSIGNED_INT triangle indices; strips become lists). The decoded sizes (meshopt's count x byteStride
// summed, Draco's claimed faces and points read from its header) are checked against the memory
// limit before anything is allocated; malformed or truncated data is an InputError naming the view
// or primitive and what broke, never a read out of bounds. The extensions' objects are removed.
void decode_compressed(tinygltf::Model& m, const DecodeContext& c);

// The image a texture shows, as an engine that reads KHR_texture_basisu and EXT_texture_webp picks
// it: the extension's image (a KTX2- or WebP-only texture names it there alone; with a fallback, the
// extension's is the one shown), else `source`; -1 for none.
int texture_image(const tinygltf::Texture& t);

}  // namespace qf::gltf_input
