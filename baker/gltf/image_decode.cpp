// KTX2 and WebP decoding to RGBA8 (see image_decode.h).
#include "gltf/image_decode.h"

#include <transcoder/basisu_transcoder.h>
#include <webp/decode.h>

#include <algorithm>
#include <cstring>
#include <mutex>

#include "core/error.h"
#include "core/input_limits.h"

namespace qf {
namespace {

constexpr std::uint32_t kMaxSide = 16384;  // the largest texture GL drivers take (the baker's atlases stop at 4096)
constexpr std::uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};

[[noreturn]] void bad(const ImageDecodeContext& c, const std::string& what) { throw InputError(c.prefix + ".image", c.path, "", what); }

void check_memory(const ImageDecodeContext& c, std::uint64_t w, std::uint64_t h, std::uint32_t levels, const char* kind) {
  check_memory_need(decoded_image_bytes({w, h, levels}), c.memory_limit, c.path, c.prefix + ".memory", "",
                    std::string("a ") + kind + " image of " + std::to_string(w) + " x " + std::to_string(h) + " texels");
}

std::uint64_t le(const std::uint8_t* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

// Checks that the header's sections (data format, key/value data, supercompression data) and every
// mip level lie within the image, in 64-bit arithmetic, before Basis Universal reads them: its own
// check adds the 32-bit key/value offset and length, which wrap, and it then allocated a key of
// 4 GB (glb fuzz target). KTX2 header: 80 bytes, the level index after it (KTX 2.0 section 3).
void check_sections(const std::uint8_t* bytes, std::size_t size, const ImageDecodeContext& c) {
  if (size < 80) bad(c, "a KTX2 image shorter than its 80-byte header");
  const auto within = [&](std::uint64_t offset, std::uint64_t length, const char* what) {
    if (offset > size || length > size - offset) bad(c, std::string("a KTX2 image whose ") + what + " reaches past its end");
  };
  within(le(bytes + 48, 4), le(bytes + 52, 4), "data format descriptor");
  within(le(bytes + 56, 4), le(bytes + 60, 4), "key/value data");
  within(le(bytes + 64, 8), le(bytes + 72, 8), "supercompression data");
  const std::uint64_t levels = std::max<std::uint64_t>(le(bytes + 40, 4), 1);
  if (levels > 16) bad(c, "a KTX2 image with " + std::to_string(levels) + " mip levels (1 to 16 expected)");
  within(80, levels * 24, "level index");
  for (std::uint64_t i = 0; i < levels; ++i) within(le(bytes + 80 + 24 * i, 8), le(bytes + 88 + 24 * i, 8), "mip level");
}

}  // namespace

bool is_ktx2(const std::uint8_t* bytes, std::size_t size) {
  return size >= sizeof(kIdentifier) && std::memcmp(bytes, kIdentifier, sizeof(kIdentifier)) == 0;
}

bool is_webp(const std::uint8_t* bytes, std::size_t size) {
  return size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

DecodedImage decode_ktx2(const std::uint8_t* bytes, std::size_t size, const ImageDecodeContext& c, bool all_levels) {
  static std::once_flag init;
  std::call_once(init, [] { basist::basisu_transcoder_init(); });
  if (size > 0xFFFFFFFFu) bad(c, "a KTX2 image over 4 GB");
  check_sections(bytes, size, c);
  basist::ktx2_transcoder t;
  if (!t.init(bytes, static_cast<std::uint32_t>(size))) bad(c, "a KTX2 image that is not a Basis Universal texture (ETC1S or UASTC)");
  if (t.get_faces() != 1 || t.get_layers() > 1) bad(c, "a KTX2 image that is a cube map or an array, not a 2D texture");
  if (t.get_levels() < 1 || t.get_levels() > 16) bad(c, "a KTX2 image with " + std::to_string(t.get_levels()) + " mip levels (1 to 16 expected)");
  // The header's size is what the RGBA8 buffers are sized by: a garbage header asked for 128 GB
  // (glb fuzz target); it is checked, with the memory its levels take, before any is allocated (a
  // 6 KB glb claiming 16384 x 16384 cost 1.18 GB before it was refused).
  if (t.get_width() < 1 || t.get_height() < 1 || t.get_width() > kMaxSide || t.get_height() > kMaxSide)
    bad(c, "a KTX2 image of " + std::to_string(t.get_width()) + " x " + std::to_string(t.get_height()) + " texels (1 to " +
               std::to_string(kMaxSide) + " a side expected)");
  const std::uint32_t levels = all_levels ? t.get_levels() : 1;
  check_memory(c, t.get_width(), t.get_height(), levels, "KTX2");
  if (!t.start_transcoding()) bad(c, "a KTX2 image whose Basis data does not decode");
  DecodedImage out;
  for (std::uint32_t level = 0; level < levels; ++level) {
    basist::ktx2_image_level_info info;
    if (!t.get_image_level_info(info, level, 0, 0)) bad(c, "a KTX2 image whose mip level " + std::to_string(level) + " is missing");
    DecodedImage img;
    img.width = static_cast<int>(info.m_orig_width);
    img.height = static_cast<int>(info.m_orig_height);
    img.rgba.resize(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 4);
    if (!t.transcode_image_level(level, 0, 0, img.rgba.data(), info.m_orig_width * info.m_orig_height,
                                 basist::transcoder_texture_format::cTFRGBA32, 0, info.m_orig_width, info.m_orig_height))
      bad(c, "a KTX2 image whose mip level " + std::to_string(level) + " does not transcode");
    if (level == 0) out = std::move(img);
    else out.mips.push_back(std::move(img));
  }
  return out;
}

DecodedImage decode_webp(const std::uint8_t* bytes, std::size_t size, const ImageDecodeContext& c) {
  WebPBitstreamFeatures f;
  // libwebp reads the header within `size` and refuses what does not fit; the RGBA buffer is sized
  // from the header's width and height (WebP caps them at 16383 a side), checked against memory first.
  if (WebPGetFeatures(bytes, size, &f) != VP8_STATUS_OK) bad(c, "a WebP image whose header does not read");
  if (f.has_animation) bad(c, "an animated WebP image, not a still texture");
  if (f.width < 1 || f.height < 1) bad(c, "a WebP image of " + std::to_string(f.width) + " x " + std::to_string(f.height) + " texels");
  check_memory(c, static_cast<std::uint64_t>(f.width), static_cast<std::uint64_t>(f.height), 1, "WebP");
  DecodedImage out;
  out.width = f.width;
  out.height = f.height;
  out.rgba.resize(static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height) * 4);
  if (!WebPDecodeRGBAInto(bytes, size, out.rgba.data(), out.rgba.size(), 4 * f.width))
    bad(c, "a WebP image of " + std::to_string(f.width) + " x " + std::to_string(f.height) + " texels whose data does not decode");
  return out;
}

}  // namespace qf
