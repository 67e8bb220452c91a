// Honest screen sizes and the recommended chain, from measurements (pure rules, no GL).
#include <gtest/gtest.h>

#include "pipeline/chain.h"
#include "pipeline/screen_sizes.h"

namespace qf {
namespace {

const std::vector<int> kSizes{128, 64, 32, 16};

std::vector<Scores> curve(std::vector<double> psnr, std::vector<double> iou) {
  std::vector<Scores> out;
  for (std::size_t i = 0; i < psnr.size(); ++i) out.push_back({psnr[i], iou[i], iou[i]});
  return out;
}

// The generated tree's finest level (663 quads, geometric 55 px), as measured: best at 64 px,
// within 1 dB at 128, mipmaps eat it at 32 and below.
TEST(ScreenSizes, WindowIsTheRunAroundTheBestThatHolds) {
  const ScreenWindow w = holding_window(kSizes, curve({19.72, 19.99, 16.64, 13.02}, {0.822, 0.804, 0.57, 0.048}));
  EXPECT_EQ(w.max_pixels, 128);
  EXPECT_EQ(w.min_pixels, 64);
  EXPECT_TRUE(w.holds_at_largest);
  EXPECT_FALSE(w.holds_at_smallest);
}

TEST(ScreenSizes, AFallingCurveHoldsOnlyWhereItIsWithinTheBar) {
  // A coarse level: best at 16 px, 1.2 dB lower at 32.
  const ScreenWindow w = holding_window(kSizes, curve({21.0, 21.8, 22.8, 24.0}, {0.88, 0.88, 0.88, 0.88}));
  EXPECT_EQ(w.max_pixels, 16);
  EXPECT_EQ(w.min_pixels, 16);
  EXPECT_TRUE(w.holds_at_smallest);
  // A lost silhouette stops the run even where PSNR holds.
  const ScreenWindow v = holding_window(kSizes, curve({20.0, 20.5, 20.2, 20.0}, {0.9, 0.9, 0.8, 0.9}));
  EXPECT_EQ(v.max_pixels, 128);
  EXPECT_EQ(v.min_pixels, 64);
  // A wider bar keeps more.
  const ScreenWindow wide = holding_window(kSizes, curve({21.0, 21.8, 22.8, 24.0}, {0.88, 0.88, 0.88, 0.88}), {2.0, 0.05});
  EXPECT_EQ(wide.max_pixels, 32);
}

TEST(ScreenSizes, CoarserLevelsStayBelowFinerOnes) {
  // Finest holds at the ladder's top: its geometric size where larger (265), else the top.
  const std::vector<ScreenWindow> w{{128, 64, true, false}, {128, 32, true, false}, {32, 16, false, true}, {32, 16, false, true}};
  const std::vector<double> honest = honest_screen_pixels({265, 127, 33, 16}, w);
  ASSERT_EQ(honest.size(), 4u);
  EXPECT_EQ(honest[0], 265);
  EXPECT_EQ(honest[1], 128);
  EXPECT_EQ(honest[2], 32);
  EXPECT_EQ(honest[3], 16);  // it held to 32 too, where the finer level looks better: halved
  // Foliage: geometric 55 px, holds to 128: the measured size, not the geometric one.
  EXPECT_EQ(honest_screen_pixels({55}, {{128, 64, true, false}})[0], 128);
}

Measurements two_files() {
  Measurements m;
  m.sizes = {64, 32, 16};
  m.views = 2;
  m.truth = 8;
  m.files = {{"big.glb", "mesh_lod", 4000, curve({40, 38, 36}, {0.99, 0.99, 0.98})},
             {"small.glb", "impostor_level", 1000, curve({25, 31, 35}, {0.85, 0.95, 0.97})}};
  return m;
}

TEST(Chain, TakesTheSmallestFileThatReachesTheBarPerBand) {
  const nlohmann::json c = recommend_chain(two_files(), 1.0);
  ASSERT_EQ(c["chain"].size(), 2u);
  EXPECT_EQ(c["chain"][0]["file"], "big.glb");
  EXPECT_EQ(c["chain"][0]["min_pixels"], 32);
  EXPECT_EQ(c["chain"][1]["file"], "small.glb");
  EXPECT_EQ(c["chain"][1]["max_pixels"], 32);
  EXPECT_EQ(c["chain"][1]["min_pixels"], 0);
  EXPECT_TRUE(c["chain"][1]["switch_distance"].is_null());
  EXPECT_DOUBLE_EQ(c["chain"][1]["error"]["psnr"].get<double>(), 31.0);
  // A bar nothing reaches: the best trade of PSNR against bytes (1 dB per doubling).
  ChainRule strict;
  strict.min_psnr = 99;
  const nlohmann::json s = recommend_chain(two_files(), 1.0, strict);
  EXPECT_EQ(s["chain"][0]["file"], "big.glb");    // 40 - 12 > 25 - 10
  EXPECT_EQ(s["chain"].back()["file"], "small.glb");  // 35 - 10 > 36 - 12
}

// The bake draws a mesh LOD or the point impostor only where it may be chosen (Scores::measured
// false elsewhere): such a file never serves a band it was not drawn at, even where it would be
// the files "made for the largest sizes"; the manifest lists it as null there.
TEST(Chain, AFileNotDrawnAtABandIsNotChosenThere) {
  Measurements m = two_files();
  m.files[0].at_size[0].measured = false;  // big.glb (made for 16 px) not drawn at 64 px
  const std::vector<double> max_pixels{16, 0};
  const nlohmann::json c = recommend_chain(m, 1.0, {}, max_pixels);
  EXPECT_EQ(c["chain"][0]["file"], "small.glb");
  EXPECT_TRUE(c["measured"][0]["at_pixels"][0].is_null());
  EXPECT_FALSE(c["measured"][0]["at_pixels"][1].is_null());
  // Both made for 8 px (valid to 16), big.glb drawn only at 16 px: above, the files made for the
  // largest sizes are those drawn there, the level alone.
  m.files[0].at_size[1].measured = false;
  const std::vector<double> both_small{8, 8};
  const nlohmann::json d = recommend_chain(m, 1.0, {}, both_small);
  ASSERT_EQ(d["chain"].size(), 1u);
  EXPECT_EQ(d["chain"][0]["file"], "small.glb");
}

TEST(Chain, SwitchDistanceIsWhereTheObjectSpansThePixels) {
  // D x H / (2 tan(fov / 2) x pixels): 1 x 1080 / (2 tan 30 deg x 32).
  EXPECT_NEAR(distance_for_pixels(1.0, 32, 1080, 60), 1080 / (2 * std::tan(3.14159265358979 / 6) * 32), 1e-9);
  EXPECT_TRUE(recommend_chain(Measurements{}, 1.0).is_null());
}

}  // namespace
}  // namespace qf
