// WebP textures (issue 32): the baker's WebP images decode in the renderer as encoded (lossless:
// exact; lossy: the alpha exact, colour close, the colour bled under alpha 0 kept); RGB images
// carry no alpha; same image, same bytes; garbage is refused naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "gltf/webp.h"
#include "runtime_gl/webp_image.h"

namespace qf::render {
namespace {

// Leaves: soft-edged green blobs with varied alpha; the texels with alpha 0 carry the colour around
// them (as the baker's extend_colors leaves them), not black.
std::vector<std::uint8_t> leaves(int side) {
  std::vector<std::uint8_t> rgba(4 * static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const double v = std::sin(0.37 * x) * std::cos(0.29 * y) + 0.5 * std::sin(0.11 * (x + 2 * y));
      std::uint8_t* p = &rgba[4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(side) + static_cast<std::size_t>(x))];
      p[0] = static_cast<std::uint8_t>(60 + x % 40), p[1] = static_cast<std::uint8_t>(140 + y % 60), p[2] = 50;
      p[3] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
    }
  return rgba;
}

// Mean absolute difference of the RGB channels over the texels with alpha 0 (`transparent`) or
// the others.
double mean_rgb(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, bool transparent) {
  double s = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); i += 4) {
    if ((a[i + 3] == 0) != transparent) continue;
    for (int c = 0; c < 3; ++c) s += std::abs(a[i + c] - b[i + c]);
    n += 3;
  }
  return n ? s / static_cast<double>(n) : 0;
}

TEST(Webp, LosslessIsExactWithTheColourUnderZeroAlpha) {
  const std::vector<std::uint8_t> in = leaves(64);
  WebpOptions o;
  o.lossless = true;
  const std::vector<std::uint8_t> bytes = encode_webp(in.data(), 64, 64, 4, o);
  ASSERT_TRUE(is_webp(bytes.data(), bytes.size()));
  const Image img = decode_webp(bytes.data(), bytes.size(), "t.webp");
  ASSERT_EQ(img.width, 64);
  ASSERT_EQ(img.height, 64);
  EXPECT_TRUE(img.mips.empty());  // WebP carries no mip levels
  EXPECT_EQ(img.rgba, in);
}

// The bake's colour setting and lossy colour (--webp-color 80): the alpha plane exact either way (the
// alpha test's cutoff turns any alpha error into coverage), and the colour under alpha 0 kept near
// (`exact`): a black or flattened fill there would be 100+ levels off and darken filtered edges.
TEST(Webp, ColourKeepsAlphaExactAndColourNear) {
  const std::vector<std::uint8_t> in = leaves(128);
  WebpOptions lossy = default_webp_color();
  lossy.lossless = false;
  lossy.quality = 80;
  for (const WebpOptions& o : {default_webp_color(), lossy}) {
    const std::vector<std::uint8_t> bytes = encode_webp(in.data(), 128, 128, 4, o);
    const Image img = decode_webp(bytes.data(), bytes.size(), "t.webp");
    ASSERT_EQ(img.rgba.size(), in.size());
    for (std::size_t i = 3; i < in.size(); i += 4) ASSERT_EQ(img.rgba[i], in[i]) << "alpha of texel " << i / 4;
    EXPECT_LT(mean_rgb(in, img.rgba, false), o.lossless ? 1e-9 : 4.0);
    EXPECT_LT(mean_rgb(in, img.rgba, true), o.lossless ? 1e-9 : 4.0);
  }
}

TEST(Webp, RgbHasNoAlpha) {
  std::vector<std::uint8_t> rgb(3 * 40 * 24);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>((i * 37) % 251);
  const std::vector<std::uint8_t> bytes = encode_webp(rgb.data(), 40, 24, 3, default_webp_normal());
  const Image img = decode_webp(bytes.data(), bytes.size(), "n.webp");
  ASSERT_EQ(img.width, 40);
  ASSERT_EQ(img.height, 24);
  for (std::size_t k = 0; k < rgb.size() / 3; ++k) {
    EXPECT_EQ(img.rgba[4 * k + 3], 255);
    if (default_webp_normal().lossless) {
      ASSERT_EQ(std::memcmp(&img.rgba[4 * k], &rgb[3 * k], 3), 0) << "texel " << k;
    }
  }
}

TEST(Webp, SameImageSameBytes) {
  const std::vector<std::uint8_t> in = leaves(96);
  for (const WebpOptions& o : {default_webp_color(), default_webp_normal()})
    EXPECT_EQ(encode_webp(in.data(), 96, 96, 4, o), encode_webp(in.data(), 96, 96, 4, o));
}

TEST(Webp, SizesWebpCannotHoldAreRefused) {
  const std::vector<std::uint8_t> in(4, 0);
  EXPECT_THROW(encode_webp(in.data(), 0, 1, 4, {}), std::invalid_argument);
  EXPECT_THROW(encode_webp(in.data(), 16384, 1, 4, {}), std::invalid_argument);
}

TEST(Webp, GarbageIsRefusedNamingTheFile) {
  const std::vector<std::uint8_t> in = leaves(32);
  const std::vector<std::uint8_t> bytes = encode_webp(in.data(), 32, 32, 4, default_webp_color());
  // Cut inside the header, cut inside the data, and the data zeroed after the RIFF header.
  std::vector<std::uint8_t> zeroed(bytes.size(), 0);
  std::copy_n(bytes.begin(), 12, zeroed.begin());
  const std::vector<std::pair<std::vector<std::uint8_t>, std::string>> bad = {
      {std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 20), "head.webp"},
      {std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2)), "half.webp"},
      {zeroed, "zero.webp"}};
  for (const auto& [b, name] : bad) {
    ASSERT_TRUE(is_webp(b.data(), b.size()));
    try {
      decode_webp(b.data(), b.size(), name);
      ADD_FAILURE() << name << " decoded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(is_webp(bytes.data(), 11));
}

}  // namespace
}  // namespace qf::render
