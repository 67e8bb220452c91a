// WebP decoding to RGBA8 (see webp_image.h).
#include "runtime_gl/webp_image.h"

#include <webp/decode.h>

#include <cstring>

#include "core/error.h"
#include "core/input_limits.h"

namespace qf::render {
namespace {

[[noreturn]] void bad(const std::string& path, const std::string& what) { throw InputError("render.gltf.image", path, "", what); }

}  // namespace

bool is_webp(const std::uint8_t* bytes, std::size_t size) {
  return size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

Image decode_webp(const std::uint8_t* bytes, std::size_t size, const std::string& path) {
  WebPBitstreamFeatures f;
  // libwebp reads the header within `size` and refuses what does not fit; the RGBA buffer is sized
  // from the header's width and height, which WebP caps at 16383 a side (1 GB at most).
  if (WebPGetFeatures(bytes, size, &f) != VP8_STATUS_OK) bad(path, "a WebP image whose header does not read");
  if (f.has_animation) bad(path, "an animated WebP image, not a still texture");
  if (f.width < 1 || f.height < 1) bad(path, "a WebP image of " + std::to_string(f.width) + " x " + std::to_string(f.height) + " texels");
  check_memory_need(decoded_image_bytes({static_cast<std::uint64_t>(f.width), static_cast<std::uint64_t>(f.height), 1}), 0, path,
                    "render.gltf.memory", "", "a WebP image of " + std::to_string(f.width) + " x " + std::to_string(f.height) + " texels");
  Image out;
  out.width = f.width;
  out.height = f.height;
  out.rgba.resize(static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height) * 4);
  if (!WebPDecodeRGBAInto(bytes, size, out.rgba.data(), out.rgba.size(), 4 * f.width))
    bad(path, "a WebP image of " + std::to_string(f.width) + " x " + std::to_string(f.height) + " texels whose data does not decode");
  return out;
}

}  // namespace qf::render
