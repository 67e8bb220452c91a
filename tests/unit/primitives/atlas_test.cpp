// Atlas packing: tiles never overlap, gutters repeat their own tile, mip blocks stay within a tile,
// texture coordinates hit the tile's texels, output is deterministic.
#include <gtest/gtest.h>

#include "primitives/atlas.h"

namespace qf {
namespace {

// A texture filled with one colour per texture (so bleeding shows), a marker in its bottom-left.
Texture solid(int w, int h, std::uint8_t tag) {
  Texture t;
  t.width = w, t.height = h;
  t.rgba.assign(4 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h), tag);
  return t;
}

std::vector<Texture> many() {
  std::vector<Texture> ts;
  for (int k = 0; k < 60; ++k) ts.push_back(solid(3 + (k * 37) % 61, 2 + (k * 53) % 47, static_cast<std::uint8_t>(k + 1)));
  return ts;
}

TEST(Atlas, TilesAndGuttersBelongToOneTexture) {
  const std::vector<Texture> ts = many();
  AtlasOptions o;
  const Atlas a = pack_atlas(ts, o);
  ASSERT_EQ(a.tiles.size(), ts.size());
  ASSERT_EQ(a.images.size(), 1u);
  const int w = a.widths[0], h = a.heights[0];
  // Every block x block block of the image holds texels of at most one texture (or none): mipmap
  // levels up to log2(block) never mix two textures.
  for (int by = 0; by < h; by += o.block)
    for (int bx = 0; bx < w; bx += o.block) {
      std::uint8_t seen = 0;
      for (int y = by; y < by + o.block; ++y)
        for (int x = bx; x < bx + o.block; ++x) {
          const std::uint8_t tag = a.images[0][4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x))];
          if (tag == 0) continue;
          if (seen == 0) seen = tag;
          ASSERT_EQ(tag, seen) << "block at " << bx << "," << by;
        }
    }
  for (std::size_t k = 0; k < ts.size(); ++k) {
    const AtlasTile& t = a.tiles[k];
    // The texture's texels, and a gutter of at least `gutter` texels around them, carry its tag.
    for (int y = t.y - o.gutter; y < t.y + t.height + o.gutter; ++y)
      for (int x = t.x - o.gutter; x < t.x + t.width + o.gutter; ++x)
        ASSERT_EQ(a.images[0][4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x))], k + 1);
    // Texture coordinates are the tile's outer texel edges.
    EXPECT_FLOAT_EQ(t.u0 * w, float(t.x));
    EXPECT_FLOAT_EQ(t.u1 * w, float(t.x + t.width));
    EXPECT_FLOAT_EQ(t.v0 * h, float(t.y));
    EXPECT_FLOAT_EQ(t.v1 * h, float(t.y + t.height));
  }
  std::size_t texels = 0;
  for (const Texture& t : ts) texels += static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
  EXPECT_EQ(a.texels, texels);
  EXPECT_EQ(pack_atlas(ts, o).images, a.images);  // deterministic
}

TEST(Atlas, RowsAreFlippedToTopDown) {
  // Texture row 0 is its bottom row (t = -half_v); images (and glTF) run top to bottom.
  Texture t = solid(2, 2, 9);
  t.rgba[0] = 77;  // texel (0, 0): bottom-left
  const Atlas a = pack_atlas({t});
  const AtlasTile& tile = a.tiles[0];
  EXPECT_EQ(a.images[0][4 * (static_cast<std::size_t>(tile.y + 1) * static_cast<std::size_t>(a.widths[0]) + static_cast<std::size_t>(tile.x))], 77);
}

TEST(Atlas, NormalMapsShareTheLayout) {
  std::vector<Texture> ts = many();
  for (Texture& t : ts) {
    t.normals = t.rgba;
    for (std::size_t k = 0; k < t.normals.size(); ++k) t.normals[k] = static_cast<std::uint8_t>(255 - t.normals[k]);
  }
  const Atlas a = pack_atlas(ts);
  ASSERT_EQ(a.normal_images.size(), a.images.size());
  for (std::size_t k = 0; k < a.images[0].size(); ++k) {
    if (a.images[0][k] != 0) {
      ASSERT_EQ(a.normal_images[0][k], 255 - a.images[0][k]);
    }
  }
  ts[3].normals.clear();
  EXPECT_TRUE(pack_atlas(ts).normal_images.empty());
}

TEST(Atlas, ManyImagesPastTheSizeLimit) {
  AtlasOptions o;
  o.max_side = 128;
  std::vector<Texture> ts;
  for (int k = 0; k < 20; ++k) ts.push_back(solid(60, 60, static_cast<std::uint8_t>(k + 1)));
  const Atlas a = pack_atlas(ts, o);
  EXPECT_GT(a.images.size(), 1u);
  for (std::size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_LE(a.widths[i], 128);
    EXPECT_LE(a.heights[i], 128);
  }
}

}  // namespace
}  // namespace qf
