// KTX2 transcoding to RGBA8 (see ktx2_image.h).
#include "runtime_gl/ktx2_image.h"

#include <transcoder/basisu_transcoder.h>

#include <algorithm>
#include <cstring>
#include <mutex>

#include "core/error.h"
#include "core/input_limits.h"

namespace qf::render {
namespace {

constexpr std::uint32_t kMaxSide = 16384;
constexpr std::uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};

[[noreturn]] void bad(const std::string& path, const std::string& what) { throw InputError("render.gltf.image", path, "", what); }

std::uint64_t le(const std::uint8_t* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

// Checks that the header's sections (data format, key/value data, supercompression data) and every
// mip level lie within the image, in 64-bit arithmetic, before Basis Universal reads them: its own
// check adds the 32-bit key/value offset and length, which wrap, and it then allocated a key of
// 4 GB (glb fuzz target). KTX2 header: 80 bytes, the level index after it (KTX 2.0 section 3).
void check_sections(const std::uint8_t* bytes, std::size_t size, const std::string& path) {
  if (size < 80) bad(path, "a KTX2 image shorter than its 80-byte header");
  const auto within = [&](std::uint64_t offset, std::uint64_t length, const char* what) {
    if (offset > size || length > size - offset) bad(path, std::string("a KTX2 image whose ") + what + " reaches past its end");
  };
  within(le(bytes + 48, 4), le(bytes + 52, 4), "data format descriptor");
  within(le(bytes + 56, 4), le(bytes + 60, 4), "key/value data");
  within(le(bytes + 64, 8), le(bytes + 72, 8), "supercompression data");
  const std::uint64_t levels = std::max<std::uint64_t>(le(bytes + 40, 4), 1);
  if (levels > 16) bad(path, "a KTX2 image with " + std::to_string(levels) + " mip levels (1 to 16 expected)");
  within(80, levels * 24, "level index");
  for (std::uint64_t i = 0; i < levels; ++i) within(le(bytes + 80 + 24 * i, 8), le(bytes + 88 + 24 * i, 8), "mip level");
}

}  // namespace

bool is_ktx2(const std::uint8_t* bytes, std::size_t size) {
  return size >= sizeof(kIdentifier) && std::memcmp(bytes, kIdentifier, sizeof(kIdentifier)) == 0;
}

Image decode_ktx2(const std::uint8_t* bytes, std::size_t size, const std::string& path) {
  static std::once_flag init;
  std::call_once(init, [] { basist::basisu_transcoder_init(); });
  if (size > 0xFFFFFFFFu) bad(path, "a KTX2 image over 4 GB");
  check_sections(bytes, size, path);
  basist::ktx2_transcoder t;
  if (!t.init(bytes, static_cast<std::uint32_t>(size))) bad(path, "a KTX2 image that is not a Basis Universal texture (ETC1S or UASTC)");
  if (t.get_faces() != 1 || t.get_layers() > 1) bad(path, "a KTX2 image that is a cube map or an array, not a 2D texture");
  if (t.get_levels() < 1 || t.get_levels() > 16) bad(path, "a KTX2 image with " + std::to_string(t.get_levels()) + " mip levels (1 to 16 expected)");
  // The header's size is what the RGBA8 buffers are sized by: a garbage header asked for 128 GB
  // (glb fuzz target). 16384 texels a side is the largest texture GL drivers take (the baker's
  // atlases stop at 4096).
  if (t.get_width() < 1 || t.get_height() < 1 || t.get_width() > kMaxSide || t.get_height() > kMaxSide)
    bad(path, "a KTX2 image of " + std::to_string(t.get_width()) + " x " + std::to_string(t.get_height()) +
                  " texels (1 to " + std::to_string(kMaxSide) + " a side expected)");
  // The RGBA8 levels' memory, from the header, against the memory available before any is
  // allocated (a 6 KB glb claiming 16384 x 16384 cost 1.18 GB before it was refused).
  check_memory_need(decoded_image_bytes({t.get_width(), t.get_height(), t.get_levels()}), 0, path, "render.gltf.memory", "",
                    "a KTX2 image of " + std::to_string(t.get_width()) + " x " + std::to_string(t.get_height()) + " texels");
  if (!t.start_transcoding()) bad(path, "a KTX2 image whose Basis data does not decode");
  Image out;
  for (std::uint32_t level = 0; level < t.get_levels(); ++level) {
    basist::ktx2_image_level_info info;
    if (!t.get_image_level_info(info, level, 0, 0)) bad(path, "a KTX2 image whose mip level " + std::to_string(level) + " is missing");
    Image img;
    img.width = static_cast<int>(info.m_orig_width);
    img.height = static_cast<int>(info.m_orig_height);
    img.rgba.resize(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 4);
    if (!t.transcode_image_level(level, 0, 0, img.rgba.data(), info.m_orig_width * info.m_orig_height,
                                 basist::transcoder_texture_format::cTFRGBA32, 0, info.m_orig_width, info.m_orig_height))
      bad(path, "a KTX2 image whose mip level " + std::to_string(level) + " does not transcode");
    if (level == 0) out = std::move(img);
    else out.mips.push_back(std::move(img));
  }
  return out;
}

}  // namespace qf::render
