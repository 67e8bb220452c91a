// JSON depth, image headers and memory needs of untrusted inputs (input_limits.h).
#include "core/input_limits.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/memory.h"

namespace qf {
namespace {

std::uint64_t be(const std::uint8_t* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = v << 8 | p[i];
  return v;
}

std::uint64_t le(const std::uint8_t* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

// JPEG: the segments up to the first start-of-frame (SOF0-15 but DHT C4, JPG C8, DAC CC), whose
// payload is precision (1 byte), height, width (2 bytes each, big-endian).
std::optional<ImageHeader> jpeg_header(const std::uint8_t* b, std::size_t size) {
  std::size_t at = 2;
  while (at + 4 <= size) {
    if (b[at] != 0xFF) return std::nullopt;
    const std::uint8_t marker = b[at + 1];
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {  // no payload
      at += 2;
      continue;
    }
    const std::size_t length = static_cast<std::size_t>(be(b + at + 2, 2));
    if (length < 2) return std::nullopt;
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (at + 9 > size) return std::nullopt;
      return ImageHeader{be(b + at + 7, 2), be(b + at + 5, 2), 1};
    }
    at += 2 + length;
  }
  return std::nullopt;
}

// WebP (RIFF "WEBP"): the first chunk says the size. VP8 (lossy): 14-bit sizes after the frame
// tag and start code; VP8L (lossless): 14-bit sizes minus one after the signature byte; VP8X
// (extended): 24-bit canvas sizes minus one.
std::optional<ImageHeader> webp_header(const std::uint8_t* b, std::size_t size) {
  if (size < 30) return std::nullopt;
  if (std::memcmp(b + 12, "VP8 ", 4) == 0) return ImageHeader{le(b + 26, 2) & 0x3FFF, le(b + 28, 2) & 0x3FFF, 1};
  if (std::memcmp(b + 12, "VP8L", 4) == 0) {
    const std::uint64_t bits = le(b + 21, 4);
    return ImageHeader{(bits & 0x3FFF) + 1, ((bits >> 14) & 0x3FFF) + 1, 1};
  }
  if (std::memcmp(b + 12, "VP8X", 4) == 0) return ImageHeader{le(b + 24, 3) + 1, le(b + 27, 3) + 1, 1};
  return std::nullopt;
}

// BMP: "BM", then the DIB header's size at 14; an OS/2 core header (12 bytes) has 16-bit sides at
// 18 and 20, the others 32-bit signed sides (a negative height is a top-down image).
std::optional<ImageHeader> bmp_header(const std::uint8_t* b, std::size_t size) {
  if (size < 26) return std::nullopt;
  if (le(b + 14, 4) == 12) return ImageHeader{le(b + 18, 2), le(b + 20, 2), 1};
  const auto side = [](std::uint64_t v) { return v >= 0x80000000u ? 0x100000000u - v : v; };  // |int32|
  return ImageHeader{side(le(b + 18, 4)), side(le(b + 22, 4)), 1};
}

// TGA has no magic number: its 18-byte header is taken as one when every field that has a small
// set of legal values has one of them (colour-map type 0 or 1, image type 1-3 or 9-11, pixel depth
// 8, 15, 16, 24 or 32; no colour map's length without a colour map). Sides are 16-bit, at 12 and 14.
std::optional<ImageHeader> tga_header(const std::uint8_t* b, std::size_t size) {
  if (size < 18 || b[1] > 1) return std::nullopt;
  const std::uint8_t type = b[2], depth = b[16];
  if (!((type >= 1 && type <= 3) || (type >= 9 && type <= 11))) return std::nullopt;
  if (depth != 8 && depth != 15 && depth != 16 && depth != 24 && depth != 32) return std::nullopt;
  if (b[1] == 0 && le(b + 5, 2) != 0) return std::nullopt;
  return ImageHeader{le(b + 12, 2), le(b + 14, 2), 1};
}

}  // namespace

std::size_t json_nesting_depth(const char* text, std::size_t size) {
  std::size_t depth = 0, deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character, a quote included
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

void check_gltf_json_depth(const std::uint8_t* bytes, std::size_t size, const std::string& path, const std::string& prefix) {
  const char* text = reinterpret_cast<const char*>(bytes);
  std::size_t length = size;
  if (size >= 4 && std::memcmp(bytes, "glTF", 4) == 0) {
    // A .glb: the JSON chunk's length at byte 12, its text from byte 20 (glTF 2.0, 4.4.3).
    if (size < 20) return;  // too short for a chunk: the parser refuses it
    length = std::min<std::size_t>(static_cast<std::size_t>(le(bytes + 12, 4)), size - 20);
    text += 20;
  }
  const std::size_t depth = json_nesting_depth(text, length);
  if (depth > kMaxJsonDepth)
    throw InputError(prefix + ".json_depth", path, "",
                     "its JSON nests " + std::to_string(depth) + " levels deep; at most " + std::to_string(kMaxJsonDepth) +
                         " are read (a glTF file needs fewer than 20)");
}

std::optional<ImageHeader> image_header(const std::uint8_t* b, std::size_t size) {
  static const std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  static const std::uint8_t kKtx2[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
  if (!b) return std::nullopt;
  if (size >= 24 && std::memcmp(b, kPng, 8) == 0 && std::memcmp(b + 12, "IHDR", 4) == 0)
    return ImageHeader{be(b + 16, 4), be(b + 20, 4), 1};
  if (size >= 4 && b[0] == 0xFF && b[1] == 0xD8) return jpeg_header(b, size);
  if (size >= 44 && std::memcmp(b, kKtx2, 12) == 0)
    return ImageHeader{le(b + 20, 4), std::max<std::uint64_t>(le(b + 24, 4), 1),
                       static_cast<std::uint32_t>(std::max<std::uint64_t>(le(b + 40, 4), 1))};
  if (size >= 12 && std::memcmp(b, "RIFF", 4) == 0 && std::memcmp(b + 8, "WEBP", 4) == 0) return webp_header(b, size);
  if (size >= 2 && b[0] == 'B' && b[1] == 'M') return bmp_header(b, size);
  return tga_header(b, size);
}

std::uint64_t decoded_image_bytes(const ImageHeader& h) {
  // Both sides are below 2^32: the product fits in 64 bits, and 4/3 of it too.
  const std::uint64_t base = h.width * h.height * 4;
  return h.levels > 1 ? base + base / 3 + 4 * h.levels : base;
}

std::size_t memory_limit(std::size_t limit, std::string* source) {
  if (limit > 0) {
    if (source) *source = "--max-memory";
    return limit;
  }
  try {
    const MemoryBudget budget = available_memory();
    if (source) *source = budget.source;
    return budget.bytes;
  } catch (const std::invalid_argument&) {
    if (source) *source = "unknown";
    return SIZE_MAX;
  }
}

void check_memory_need(std::uint64_t need, std::size_t limit, const std::string& path, const std::string& code,
                       const std::string& where, const std::string& what) {
  std::string source;
  const std::size_t allowed = memory_limit(limit, &source);
  if (need <= allowed) return;
  throw InputError(code, path, where,
                   what + " would need about " + format_bytes(static_cast<double>(need)) + ", but only " +
                       format_bytes(static_cast<double>(allowed)) + " is " + (limit > 0 ? "allowed" : "available") + " (" +
                       source + "); nothing was allocated");
}

void check_glb_chunks(const std::uint8_t* bytes, std::size_t size, const std::string& path, const std::string& code) {
  if (size < 20 || std::memcmp(bytes, "glTF", 4) != 0) return;
  // glTF 2.0, 4.4.3: header (magic, version, total length), the JSON chunk (length, type, text),
  // then the BIN chunk (length, type, data). The parser refuses a JSON chunk past the end.
  const std::uint64_t total = le(bytes + 8, 4), bin_at = 20 + le(bytes + 12, 4);
  const std::uint64_t end = std::min<std::uint64_t>(total, size);
  if (bin_at + 8 > end) return;  // no BIN chunk (or no room for its header: the parser says so)
  const std::uint64_t bin_end = bin_at + 8 + le(bytes + bin_at, 4);
  if (bin_end > end)
    throw InputError(code, path, "byte " + std::to_string(bin_at),
                     "the BIN chunk's " + std::to_string(bin_end - bin_at - 8) + " bytes end at byte " + std::to_string(bin_end) +
                         ", past the file's " + std::to_string(end));
}

}  // namespace qf
