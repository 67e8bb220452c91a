// WebP images (EXT_texture_webp) for the renderer: decoded to RGBA8 as an engine decodes them, so
// that every figure the project measures (qf-render eval, the bake's own measuring of screen sizes,
// the chain) draws the WebP files. A WebP image carries no mip levels: the renderer makes them by
// box filtering, as for a PNG. The decoding is the shared one (gltf/image_decode.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "runtime_gl/scene.h"

namespace qf::render {

// Whether `bytes` start as a WebP file does ("RIFF", a size, "WEBP").
bool is_webp(const std::uint8_t* bytes, std::size_t size);

// The image as RGBA8 (alpha 255 where the file has none). Throws InputError ("render.gltf.image")
// naming `path` and what is wrong for bytes that are not a decodable still WebP image.
Image decode_webp(const std::uint8_t* bytes, std::size_t size, const std::string& path);

}  // namespace qf::render
