// KTX2 (KHR_texture_basisu: Basis Universal's transcoder) and WebP (EXT_texture_webp: libwebp)
// images decoded to RGBA8, for the baker's glTF reader (io/gltf_read.cpp, input textures) and
// runtime_gl's loader (every figure the project measures draws compressed files as an engine
// would). The transcoder and libwebp live in image_decode.cpp alone. Before any texel buffer is
// allocated, the header's size is checked against 16384 a side and the memory limit
// (core/input_limits.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace qf {

// Rows top to bottom, 4 bytes a texel; `mips`: levels 1.. of a file that carries its own (KTX2).
struct DecodedImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::vector<DecodedImage> mips = {};
};

// Whether `bytes` start with the KTX2 file identifier.
bool is_ktx2(const std::uint8_t* bytes, std::size_t size);
// Whether `bytes` start as a WebP file does ("RIFF", a size, "WEBP").
bool is_webp(const std::uint8_t* bytes, std::size_t size);

// Errors are InputError(`prefix` + ".image", path) saying what is wrong, or `prefix` + ".memory"
// when the decoded texels would pass memory_limit(`memory_limit`) (0: the memory available).
struct ImageDecodeContext {
  std::string path;    // the file the image is in
  std::string prefix;  // "gltf" (baker) or "render.gltf" (runtime)
  std::size_t memory_limit = 0;
};

// A 2D Basis Universal KTX2 texture (ETC1S or UASTC) transcoded to RGBA8: level 0 and, with
// `all_levels`, every mip level the file carries.
DecodedImage decode_ktx2(const std::uint8_t* bytes, std::size_t size, const ImageDecodeContext& c, bool all_levels = true);

// A still WebP image as RGBA8 (alpha 255 where the file has none).
DecodedImage decode_webp(const std::uint8_t* bytes, std::size_t size, const ImageDecodeContext& c);

}  // namespace qf
