// PNG encoding in memory (OpenImageIO): the atlas images embedded in the .glb files.
#pragma once

#include <cstdint>
#include <vector>

namespace qf {

// Encodes an 8-bit image, rows top to bottom, `channels` per texel (3 or 4). The same pixels give
// the same bytes (OIIO's PNG writer is deterministic). Throws std::runtime_error on failure.
std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels);

}  // namespace qf
