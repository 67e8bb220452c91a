// Images in memory through OpenImageIO: PNG encoding of the atlas images embedded in the .glb files,
// and decoding of input textures. OpenImageIO lives in the plug-in libqf_png.so, loaded on the
// first call (see png.cpp for why).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"

namespace qf {

// Encodes an 8-bit image, rows top to bottom, `channels` per texel (3 or 4). The same pixels give
// the same bytes (OIIO's PNG writer is deterministic).
// Throws std::runtime_error on failure, or when the plug-in cannot be loaded.
std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels);

// Decodes a PNG, JPEG or any other image OpenImageIO reads (PNG and JPEG known by their bytes, others
// by the extension of `name`) to 8-bit RGBA with straight alpha, rows top to bottom. Throws
// std::runtime_error saying what failed (the caller names the file).
TextureImage decode_image(const std::uint8_t* bytes, std::size_t size, const std::string& name);

// Loads the plug-in now (throws as encode_png): a process that forks bakers loads it once, before.
void preload_png_encoder();

}  // namespace qf
