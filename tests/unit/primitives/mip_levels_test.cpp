// Coverage-preserving mip levels: every level shows the base level's share of texels at the
// cutoff (as near as any scale of its alpha can), empty texels never darken the colour, normals
// stay unit length, same input same bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "primitives/mip_levels.h"

namespace qf {
namespace {

// Foliage: opaque leaves (short one- and two-texel wide strokes) on an empty background, the
// background black with alpha 0 (as an atlas's unused space is), leaves green.
TextureImage foliage(int side, std::uint32_t seed) {
  TextureImage t;
  t.width = t.height = side;
  t.rgba.assign(4 * static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0);
  std::uint32_t s = seed;
  auto next = [&s] { s = s * 1664525u + 1013904223u; return s >> 8; };
  for (int leaf = 0; leaf < side * side / 24; ++leaf) {
    int x = static_cast<int>(next() % static_cast<std::uint32_t>(side)), y = static_cast<int>(next() % static_cast<std::uint32_t>(side));
    const int dx = static_cast<int>(next() % 3) - 1, dy = static_cast<int>(next() % 3) - 1, length = 2 + static_cast<int>(next() % 5);
    const auto alpha = static_cast<std::uint8_t>(160 + next() % 96);
    for (int k = 0; k < length; ++k, x += dx, y += dy) {
      if (x < 0 || y < 0 || x >= side || y >= side) break;
      std::uint8_t* p = &t.rgba[4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(side) + static_cast<std::size_t>(x))];
      p[0] = 40, p[1] = 170, p[2] = 60, p[3] = std::max(p[3], alpha);
    }
  }
  return t;
}

// Plain box filtering of alpha (what an engine's mipmap generation does), for comparison.
TextureImage box_half(const TextureImage& a) {
  TextureImage b;
  b.width = std::max(1, a.width / 2), b.height = std::max(1, a.height / 2);
  b.rgba.assign(4 * static_cast<std::size_t>(b.width) * static_cast<std::size_t>(b.height), 0);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) {
      int sum = 0;
      for (int k = 0; k < 4; ++k) sum += a.rgba[4 * (static_cast<std::size_t>(2 * y + (k >> 1)) * static_cast<std::size_t>(a.width) + static_cast<std::size_t>(2 * x + (k & 1))) + 3];
      b.rgba[4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(b.width) + static_cast<std::size_t>(x)) + 3] = static_cast<std::uint8_t>((sum + 2) / 4);
    }
  return b;
}

TEST(MipLevels, ChainHalvesDownToOneTexel) {
  const std::vector<TextureImage> chain = mip_levels(foliage(64, 1), {MipOptions::Kind::kColor, 0.3f});
  ASSERT_EQ(chain.size(), 7u);
  for (std::size_t k = 0; k < chain.size(); ++k) {
    EXPECT_EQ(chain[k].width, 64 >> k);
    EXPECT_EQ(chain[k].rgba.size(), 4u * static_cast<std::size_t>(chain[k].width) * static_cast<std::size_t>(chain[k].height));
  }
  // A non-square, non-power-of-two base: sizes halve and stop at 1 on each side.
  TextureImage odd = foliage(64, 2);
  odd.width = 24, odd.height = 5;
  odd.rgba.resize(4u * 24 * 5);
  const std::vector<TextureImage> c2 = mip_levels(odd, {});
  ASSERT_EQ(c2.size(), 5u);
  EXPECT_EQ(c2[1].width, 12);
  EXPECT_EQ(c2[1].height, 2);
  EXPECT_EQ(c2[4].width, 1);
  EXPECT_EQ(c2[4].height, 1);
}

TEST(MipLevels, CoverageKeptAtTheCutoff) {
  for (const float cutoff : {0.2f, 0.3f, 0.5f}) {
    const TextureImage base = foliage(128, 7);
    const double c0 = alpha_coverage(base, cutoff);
    ASSERT_GT(c0, 0.1);
    ASSERT_LT(c0, 0.6);
    const std::vector<TextureImage> chain = mip_levels(base, {MipOptions::Kind::kColor, cutoff});
    EXPECT_EQ(alpha_coverage(chain[0], cutoff), c0);
    TextureImage box = base;
    double box_error = 0;
    for (std::size_t k = 1; k < chain.size(); ++k) {
      box = box_half(box);
      const double texels = static_cast<double>(chain[k].width) * chain[k].height;
      const double kept = alpha_coverage(chain[k], cutoff);
      // Down to 8x8 the leaves' alpha takes enough distinct values that some scale hits the base
      // coverage within one texel's share (two texels at the last levels, where bytes tie).
      if (chain[k].width >= 8) {
        EXPECT_LE(std::abs(kept - c0), (chain[k].width >= 32 ? 1.0 : 2.0) / texels + 1e-12) << "cutoff " << cutoff << " level " << k;
      }
      // Plain box filtering loses (or, at low cutoffs, gains) much more: what the scale repairs.
      if (chain[k].width >= 8) box_error = std::max(box_error, std::abs(alpha_coverage(box, cutoff) - c0));
    }
    EXPECT_GT(box_error, 0.1) << "cutoff " << cutoff;
  }
}

TEST(MipLevels, EmptyTexelsDoNotDarkenColour) {
  // Black, empty background; every leaf green: every level's every texel must read green, alpha
  // 0 or not (bilinear filtering mixes a covered texel with its empty neighbours).
  const TextureImage base = foliage(64, 3);
  for (const std::vector<TextureImage>& chain : {mip_levels(base, {MipOptions::Kind::kColor, 0.3f}), mip_levels(base, {MipOptions::Kind::kColor, 0})})
    for (const TextureImage& level : chain)
      for (std::size_t i = 0; i < level.rgba.size(); i += 4) {
        ASSERT_NEAR(level.rgba[i + 0], 40, 1) << level.width;
        ASSERT_NEAR(level.rgba[i + 1], 170, 1) << level.width;
        ASSERT_NEAR(level.rgba[i + 2], 60, 1) << level.width;
      }
}

TEST(MipLevels, ColourAveragesInLinearLight) {
  // A black and white checker (opaque): the 2x2 mean is linear 0.5, sRGB byte 188, not 128.
  TextureImage t;
  t.width = t.height = 2;
  t.rgba = {0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 255};
  const std::vector<TextureImage> chain = mip_levels(t, {MipOptions::Kind::kColor, 0});
  ASSERT_EQ(chain.size(), 2u);
  EXPECT_EQ(chain[1].rgba[0], 188);
  EXPECT_EQ(chain[1].rgba[3], 255);
  // Linear channels average their bytes.
  EXPECT_EQ(mip_levels(t, {MipOptions::Kind::kLinear, 0})[1].rgba[0], 128);
}

// A wavy tangent-space normal map, 16 x 16.
TextureImage normal_map() {
  TextureImage n;
  n.width = n.height = 16;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const double ax = std::sin(0.9 * x) * 0.7, ay = std::cos(1.3 * y) * 0.6;
      const double len = std::sqrt(ax * ax + ay * ay + 1);
      for (double v : {ax / len, ay / len, 1 / len}) n.rgba.push_back(static_cast<std::uint8_t>(std::lround((v * 0.5 + 0.5) * 255)));
      n.rgba.push_back(255);
    }
  return n;
}

TEST(MipLevels, NormalsStayUnitLength) {
  for (const TextureImage& level : mip_levels(normal_map(), {MipOptions::Kind::kNormal, 0}))
    for (std::size_t i = 0; i < level.rgba.size(); i += 4) {
      double len2 = 0;
      for (int c = 0; c < 3; ++c) len2 += std::pow(level.rgba[i + static_cast<std::size_t>(c)] / 127.5 - 1, 2);
      EXPECT_NEAR(std::sqrt(len2), 1.0, 0.02) << level.width;
      EXPECT_EQ(level.rgba[i + 3], 255);
    }
}

// A normal map is stored at half size (glb.cpp): the chain's second level, made alone.
TEST(MipLevels, HalfLevelIsTheChainsSecond) {
  const TextureImage n = normal_map();
  const TextureImage half = half_level(n, {MipOptions::Kind::kNormal, 0});
  EXPECT_EQ(half.width, 8);
  EXPECT_EQ(half.height, 8);
  EXPECT_EQ(half.rgba, mip_levels(n, {MipOptions::Kind::kNormal, 0})[1].rgba);
}

TEST(MipLevels, Deterministic) {
  const TextureImage base = foliage(64, 11);
  const std::vector<TextureImage> a = mip_levels(base, {MipOptions::Kind::kColor, 0.3f});
  const std::vector<TextureImage> b = mip_levels(base, {MipOptions::Kind::kColor, 0.3f});
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].rgba, b[k].rgba);
}

}  // namespace
}  // namespace qf
