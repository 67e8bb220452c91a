// What an untrusted input may cost, judged before it is parsed or decoded: the nesting depth of
// its JSON (parsers recurse per level), an image's decoded size from its header, and a memory
// need against the memory limit. Shared by the baker's readers and runtime_gl's loader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace qf {

// Deepest JSON nesting read. tinygltf's parser recurses once per level and overflowed the stack
// at ~14,500 (8 MB stack); real glTF files nest less than 20 deep.
constexpr std::size_t kMaxJsonDepth = 512;

// The deepest nesting of objects and arrays in `size` bytes of JSON text (brackets inside strings
// do not count). Linear, no allocation; malformed text gets a figure too (the parser refuses it).
std::size_t json_nesting_depth(const char* text, std::size_t size);

// Throws InputError("<prefix>.json_depth", path) when the JSON of a .gltf (the whole text) or a
// .glb (its JSON chunk; `bytes` starting "glTF") nests deeper than kMaxJsonDepth. Call it before
// any JSON parser sees the bytes.
void check_gltf_json_depth(const std::uint8_t* bytes, std::size_t size, const std::string& path, const std::string& prefix);

// Throws InputError(code, path) when a .glb (`bytes` starting "glTF") has a BIN chunk whose
// declared length reaches past the file or past the header's total length. tinygltf 2.x checks the
// chunk's length without its 8-byte chunk header and then copies a buffer of that length from
// 8 bytes past where its check ended: a file whose BIN chunk and buffer claim those 8 bytes was
// read past its end (found by fuzz_gltf, issue 50). Anything else is left to the parser.
void check_glb_chunks(const std::uint8_t* bytes, std::size_t size, const std::string& path, const std::string& code);

// An image's size as its header declares it: PNG (IHDR), JPEG (the first SOF segment), KTX2
// (pixelWidth, pixelHeight, levelCount), WebP (VP8, VP8L, VP8X), BMP and TGA (a TGA header is
// recognised by its fields' legal values: it has no magic number). nullopt for other formats or
// a header that does not read (the decoder then says why).
struct ImageHeader {
  std::uint64_t width = 0, height = 0;
  std::uint32_t levels = 1;  // KTX2's mip levels; 1 for the others
};
std::optional<ImageHeader> image_header(const std::uint8_t* bytes, std::size_t size);

// Bytes the image takes decoded to RGBA8, its mip levels included (each a quarter of the one
// before; an upper bound of 4/3 of the base level).
std::uint64_t decoded_image_bytes(const ImageHeader& h);

// The memory limit: `limit` when non-zero (--max-memory), else the memory available
// (core/memory.h available_memory: MemAvailable, the cgroup, QF_MEMORY_LIMIT). `source` gets
// where it came from. A malformed QF_MEMORY_LIMIT counts as no limit here (the bake's plan
// reports it as bad usage).
std::size_t memory_limit(std::size_t limit, std::string* source = nullptr);

// Throws InputError(code, path, where, ...) saying what `need` bytes of `what` would have taken
// and what the limit allows, when need exceeds memory_limit(limit). Nothing is allocated.
void check_memory_need(std::uint64_t need, std::size_t limit, const std::string& path, const std::string& code,
                       const std::string& where, const std::string& what);

}  // namespace qf
