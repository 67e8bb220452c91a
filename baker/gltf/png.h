// PNG encoding in memory (OpenImageIO): the atlas images embedded in the .glb files. OpenImageIO
// lives in the plug-in libqf_png.so, loaded on the first call (see png.cpp for why).
#pragma once

#include <cstdint>
#include <vector>

namespace qf {

// Encodes an 8-bit image, rows top to bottom, `channels` per texel (3 or 4). The same pixels give
// the same bytes (OIIO's PNG writer is deterministic).
// Throws std::runtime_error on failure, or when the plug-in cannot be loaded.
std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels);

// Loads the plug-in now (throws as encode_png): a process that forks bakers loads it once, before.
void preload_png_encoder();

}  // namespace qf
