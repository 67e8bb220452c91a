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

// By measurement (docs/textures.md, "WebP settings, by measurement": bunny00's vertices, the
// coloured scan b9_training, the generated bush and a 1M-point torus, each level at its own size
// against PNG). Colour + alpha: lossless. Lossy colour (quality 70..95, the alpha plane lossless,
// `exact`) stayed within -0.02..+0.12 dB on the first three, but the torus's colour pattern lost
// 0.28..0.44 dB at every level (90 and 80), past the 0.3 dB bound; lossless costs nothing there and
// is no larger on point sets (their colour is smooth and the exact alpha plane dominates: 1..3%
// smaller than lossy 80..90 on the torus, bunny and b9). Only textured meshes pay: the bush's leaf colour is 75%
// larger than at 80 (--webp-color 80 for those). `exact` keeps the colour bled under alpha 0
// (TextureOptions::extend_colors), which lossless would otherwise zero and the engine's bilinear
// filter and box-filtered mips would then mix in as a dark fringe.
WebpOptions default_webp_color() {
  WebpOptions o;
  o.lossless = true;
  o.quality = 75;  // libwebp's default effort
  o.alpha_quality = 100;
  o.exact = true;
  return o;
}

// Normal maps: lossy at 90, 62% fewer bytes than lossless (bunny00: 98 KB against 261 KB) for
// -0.06..-0.10 dB; 95 took 26% more for no better; 80 lost up to 0.17 dB. Near-lossless saved
// nothing over lossless.
WebpOptions default_webp_normal() {
  WebpOptions o;
  o.lossless = false;
  o.quality = 90;
  return o;
}

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
