// KTX2 images (KHR_texture_basisu) for the renderer: a Basis Universal texture transcoded to
// RGBA8 with every mip level the file carries, so that every figure the project measures (qf-render
// eval, the bake's own measuring of screen sizes, the chain) draws the compressed files as an
// engine would. The transcoding is the baker's and runtime's shared decoder (gltf/image_decode.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "runtime_gl/scene.h"

namespace qf::render {

// Whether `bytes` start with the KTX2 file identifier.
bool is_ktx2(const std::uint8_t* bytes, std::size_t size);

// The image: level 0 in Image::rgba, the others in Image::mips. Throws InputError
// ("render.gltf.image", "render.gltf.memory") naming `path` and what is wrong for a file that is
// not a 2D Basis Universal KTX2 texture or does not transcode.
Image decode_ktx2(const std::uint8_t* bytes, std::size_t size, const std::string& path);

}  // namespace qf::render
