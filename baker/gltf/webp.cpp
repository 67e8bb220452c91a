// libwebp's encoder behind encode_webp (webp.h); its header stays in this file.
#include "gltf/webp.h"

#include <webp/encode.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace qf {
namespace {

// Frees the picture and the writer's buffer on every way out.
struct Encoding {
  WebPPicture picture;
  WebPMemoryWriter writer;
  Encoding() {
    WebPPictureInit(&picture);
    WebPMemoryWriterInit(&writer);
  }
  ~Encoding() {
    WebPPictureFree(&picture);
    WebPMemoryWriterClear(&writer);
  }
  Encoding(const Encoding&) = delete;
  Encoding& operator=(const Encoding&) = delete;
};

WebPConfig config_of(const WebpOptions& o) {
  WebPConfig c;
  if (!WebPConfigInit(&c)) throw std::runtime_error("WebP encoding: libwebp's version does not match its header");
  c.lossless = o.lossless ? 1 : 0;
  c.quality = static_cast<float>(std::clamp(o.quality, 0, 100));
  c.method = std::clamp(o.method, 0, 6);
  c.alpha_quality = std::clamp(o.alpha_quality, 0, 100);
  c.exact = o.exact ? 1 : 0;
  c.use_sharp_yuv = o.sharp_yuv ? 1 : 0;
  c.near_lossless = std::clamp(o.near_lossless, 0, 100);
  // One thread: the bytes must not depend on the machine (and the bake's levels are encoded one
  // at a time beside nothing else).
  c.thread_level = 0;
  if (!WebPValidateConfig(&c)) throw std::runtime_error("WebP encoding: libwebp refused the settings");
  return c;
}

}  // namespace

std::vector<std::uint8_t> encode_webp(const std::uint8_t* pixels, int w, int h, int channels, const WebpOptions& options) {
  if (w < 1 || h < 1 || w > WEBP_MAX_DIMENSION || h > WEBP_MAX_DIMENSION)
    throw std::invalid_argument("WebP encoding: an image of " + std::to_string(w) + " x " + std::to_string(h) +
                                " texels (1 to " + std::to_string(WEBP_MAX_DIMENSION) + " a side)");
  if (channels != 3 && channels != 4) throw std::invalid_argument("WebP encoding: 3 or 4 channels, not " + std::to_string(channels));
  const WebPConfig config = config_of(options);
  Encoding e;
  e.picture.width = w;
  e.picture.height = h;
  // ARGB in: WebPEncode converts to YUV itself for lossy, with the sharp conversion when asked.
  e.picture.use_argb = 1;
  const int ok = channels == 4 ? WebPPictureImportRGBA(&e.picture, pixels, 4 * w) : WebPPictureImportRGB(&e.picture, pixels, 3 * w);
  if (!ok) throw std::runtime_error("WebP encoding: out of memory importing " + std::to_string(w) + " x " + std::to_string(h) + " texels");
  e.picture.writer = WebPMemoryWrite;
  e.picture.custom_ptr = &e.writer;
  if (!WebPEncode(&config, &e.picture))
    throw std::runtime_error("WebP encoding: libwebp failed (error " + std::to_string(static_cast<int>(e.picture.error_code)) + ")");
  return std::vector<std::uint8_t>(e.writer.mem, e.writer.mem + e.writer.size);
}

}  // namespace qf
