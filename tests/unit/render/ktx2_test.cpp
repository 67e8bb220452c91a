// KTX2 textures (issue 32): the baker's Basis Universal files decode in the renderer with every mip
// level, close to what was encoded, keeping the levels' coverage at the cutoff; the same bytes at
// any thread count; a level written with KTX2 loads with its mips; garbage is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

#include "core/error.h"
#include "gltf/glb.h"
#include "gltf/ktx2.h"
#include "primitives/mip_levels.h"
#include "runtime_gl/ktx2_image.h"

namespace qf::render {
namespace {

// Leaves: soft-edged green blobs with varied alpha on an empty background.
TextureImage leaves(int side) {
  TextureImage t;
  t.width = t.height = side;
  t.rgba.assign(4 * static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const double v = std::sin(0.37 * x) * std::cos(0.29 * y) + 0.5 * std::sin(0.11 * (x + 2 * y));
      std::uint8_t* p = &t.rgba[4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(side) + static_cast<std::size_t>(x))];
      p[0] = static_cast<std::uint8_t>(60 + x % 40), p[1] = static_cast<std::uint8_t>(140 + y % 60), p[2] = 50;
      p[3] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
    }
  return t;
}

double mean_abs(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += std::abs(a[i] - b[i]);
  return s / static_cast<double>(a.size());
}

class Ktx2RoundTrip : public ::testing::TestWithParam<BasisCodec> {};

TEST_P(Ktx2RoundTrip, EveryLevelDecodesCloseWithItsCoverage) {
  const float cutoff = 0.3f;
  const std::vector<TextureImage> levels = mip_levels(leaves(64), {MipOptions::Kind::kColor, cutoff});
  Ktx2Options o;
  o.codec = GetParam();
  const std::vector<std::uint8_t> bytes = encode_ktx2(levels, o);
  ASSERT_TRUE(is_ktx2(bytes.data(), bytes.size()));
  const Image img = decode_ktx2(bytes.data(), bytes.size(), "t.ktx2");
  ASSERT_EQ(img.mips.size() + 1, levels.size());
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const Image& d = k == 0 ? img : img.mips[k - 1];
    ASSERT_EQ(d.width, levels[k].width);
    ASSERT_EQ(d.height, levels[k].height);
    // Lossy, but near on this busy image (a colour ramp every 40 texels): a few levels of 255 on
    // average (ETC1S more than UASTC); a wrong level, channel order or row order is 30+ off.
    EXPECT_LT(mean_abs(d.rgba, levels[k].rgba), o.codec == BasisCodec::kUastc ? 6.0 : 10.0) << "level " << k;
    // The coverage the chain kept survives the codec: within 3% of the texels (from 8x8 up).
    if (d.width >= 8) {
      EXPECT_NEAR(alpha_coverage(TextureImage{d.width, d.height, d.rgba}, cutoff), alpha_coverage(levels[0], cutoff), 0.03) << "level " << k;
    }
  }
}

TEST_P(Ktx2RoundTrip, SameBytesAtAnyThreadCount) {
  const std::vector<TextureImage> levels = mip_levels(leaves(128), {MipOptions::Kind::kColor, 0.3f});
  Ktx2Options o;
  o.codec = GetParam();
  o.threads = 1;
  const std::vector<std::uint8_t> one = encode_ktx2(levels, o);
  o.threads = 3;
  EXPECT_EQ(encode_ktx2(levels, o), one);
}

INSTANTIATE_TEST_SUITE_P(Codecs, Ktx2RoundTrip, ::testing::Values(BasisCodec::kEtc1s, BasisCodec::kUastc),
                         [](const ::testing::TestParamInfo<BasisCodec>& i) { return std::string(basis_codec_name(i.param)); });

TEST(Ktx2, GarbageIsRefused) {
  const std::vector<std::uint8_t> bytes = encode_ktx2(mip_levels(leaves(16)), {});
  EXPECT_THROW(decode_ktx2(bytes.data(), 40, "cut.ktx2"), InputError);  // cut inside the header
  std::vector<std::uint8_t> zeroed(bytes.size(), 0);                      // the identifier, then nothing
  std::copy_n(bytes.begin(), 12, zeroed.begin());
  try {
    decode_ktx2(zeroed.data(), zeroed.size(), "zero.ktx2");
    ADD_FAILURE() << "a KTX2 file of zeros decoded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("zero.ktx2"), std::string::npos) << e.what();
  }
}

// A header asking for more texels than any texture holds is refused before anything is allocated
// for them (the glb fuzz target's 128 GB request).
TEST(Ktx2, HugeSizeIsRefused) {
  std::vector<std::uint8_t> bytes = encode_ktx2(mip_levels(leaves(16)), {});
  const std::uint32_t huge = 1u << 20;
  std::memcpy(bytes.data() + 20, &huge, 4);  // pixelWidth (after the identifier, vkFormat and typeSize)
  try {
    decode_ktx2(bytes.data(), bytes.size(), "huge.ktx2");
    ADD_FAILURE() << "a KTX2 file of 2^20 texels a side decoded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a side expected"), std::string::npos) << e.what();
  }
}

// Sections whose offset and length wrap in 32 bits are refused before Basis Universal reads them
// (the glb fuzz target: a key/value section that wrapped made it allocate a 4 GB key).
TEST(Ktx2, SectionPastTheEndIsRefused) {
  const std::vector<std::uint8_t> good = encode_ktx2(mip_levels(leaves(16)), {});
  const std::uint32_t offset = 0xFFFFFFF0u, length = 0x20u;  // offset + length wraps to 16
  for (const std::size_t at : {std::size_t{48}, std::size_t{56}}) {  // data format descriptor, key/value data
    std::vector<std::uint8_t> bytes = good;
    std::memcpy(bytes.data() + at, &offset, 4);
    std::memcpy(bytes.data() + at + 4, &length, 4);
    try {
      decode_ktx2(bytes.data(), bytes.size(), "wrap.ktx2");
      ADD_FAILURE() << "a section wrapping past the end decoded (field at " << at << ")";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("reaches past its end"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace qf::render
