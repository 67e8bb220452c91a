// The CPU mip chains draw_gl11 uploads (runtime_gl/mip_chain): sizes, box filter, premultiplication.
#include <gtest/gtest.h>

#include "runtime_gl/mip_chain.h"

namespace qf::render {
namespace {

TEST(MipChain, HalvesDownToOnePixelAndAveragesBoxes) {
  // 4x2: left half black, right half white (opaque).
  Image base{4, 2, {}};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (std::uint8_t v : {std::uint8_t(x < 2 ? 0 : 255), std::uint8_t(x < 2 ? 0 : 255), std::uint8_t(x < 2 ? 0 : 255), std::uint8_t(255)})
        base.rgba.push_back(v);
  const std::vector<Image> chain = mip_chain(base, /*premultiply=*/false);
  ASSERT_EQ(chain.size(), 3u);  // 4x2, 2x1, 1x1
  EXPECT_EQ(chain[0].rgba, base.rgba);
  EXPECT_EQ(chain[1].width, 2);
  EXPECT_EQ(chain[1].height, 1);
  EXPECT_EQ(chain[1].rgba, (std::vector<std::uint8_t>{0, 0, 0, 255, 255, 255, 255, 255}));
  EXPECT_EQ(chain[2].width, 1);
  EXPECT_EQ(chain[2].height, 1);
  // (0 + 255 + 2) / 4 rounds 127.5 up to 128 over the 2x2 box of its 2x1 parent (last column repeated).
  EXPECT_EQ(chain[2].rgba[0], (0 + 0 + 255 + 255 + 2) / 4);
  EXPECT_EQ(chain[2].rgba[3], 255);
}

TEST(MipChain, PremultipliesByAlphaBeforeFiltering) {
  const Image base{1, 1, {200, 100, 50, 128}};
  const std::vector<Image> chain = mip_chain(base, /*premultiply=*/true);
  ASSERT_EQ(chain.size(), 1u);
  EXPECT_EQ(chain[0].rgba, (std::vector<std::uint8_t>{(200 * 128 + 127) / 255, (100 * 128 + 127) / 255, (50 * 128 + 127) / 255, 128}));
}

}  // namespace
}  // namespace qf::render
