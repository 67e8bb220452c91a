// The renderer's view of the shared KTX2 and WebP decoders (ktx2_image.h, webp_image.h).
#include "runtime_gl/ktx2_image.h"

#include "gltf/image_decode.h"
#include "runtime_gl/webp_image.h"

namespace qf::render {
namespace {

Image to_render_image(DecodedImage&& d) {
  Image out{d.width, d.height, std::move(d.rgba)};
  for (DecodedImage& m : d.mips) out.mips.push_back(to_render_image(std::move(m)));
  return out;
}

}  // namespace

bool is_ktx2(const std::uint8_t* bytes, std::size_t size) { return qf::is_ktx2(bytes, size); }
bool is_webp(const std::uint8_t* bytes, std::size_t size) { return qf::is_webp(bytes, size); }

Image decode_ktx2(const std::uint8_t* bytes, std::size_t size, const std::string& path) {
  return to_render_image(qf::decode_ktx2(bytes, size, {path, "render.gltf", 0}));
}

Image decode_webp(const std::uint8_t* bytes, std::size_t size, const std::string& path) {
  return to_render_image(qf::decode_webp(bytes, size, {path, "render.gltf", 0}));
}

}  // namespace qf::render
