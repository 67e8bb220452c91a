// Honest screen sizes and the recommended chain, from measurements (pure rules, no GL): every file
// judged beside the asset as drawn, never held where it draws nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "measure/chain.h"
#include "measure/screen_sizes.h"

namespace qf {
namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
const std::vector<int> kSizes{128, 64, 32, 16};

Scores score(double psnr, double soft_iou, double coverage) { return {psnr, soft_iou, soft_iou, coverage, true}; }

std::vector<Scores> curve(std::vector<double> psnr, std::vector<double> soft_iou, std::vector<double> coverage) {
  std::vector<Scores> out;
  for (std::size_t i = 0; i < psnr.size(); ++i) out.push_back(score(psnr[i], soft_iou[i], coverage[i]));
  return out;
}

// The asset as an engine draws it: its own mipmaps thin it as it shrinks.
const std::vector<Scores> kAsset = curve({30, 28, 24, 22}, {0.95, 0.9, 0.8, 0.7}, {1.0, 0.95, 0.9, 0.8});

// A level that draws nothing scores a fine PSNR on a frame that is mostly background (the lattice
// tower's 1220-quad level: 22.1 dB at 16 px, covering nothing): it must not hold there.
TEST(ScreenSizes, ALevelThatDrawsNothingNeverHolds) {
  const Scores asset = score(12, 0.3, 1.4), empty = score(24, 0.0, 0.0);
  EXPECT_FALSE(holds(empty, asset));
  EXPECT_FALSE(holds(score(24, 0.3, 0.49), asset)) << "under half of the truth's coverage";
  EXPECT_TRUE(holds(score(24, 0.3, 0.8), asset));
}

// Two empty pictures are no evidence: where the truth covers nothing, no file holds.
TEST(ScreenSizes, NoEvidenceIsNoMatch) {
  const Scores blank{kNone, kNone, kNone, kNone, true};
  EXPECT_FALSE(blank.evidence());
  EXPECT_FALSE(holds(blank, blank));
  EXPECT_FALSE(holds(score(30, 1, 1), blank));
  Scores not_drawn = score(30, 1, 1);
  not_drawn.measured = false;
  EXPECT_FALSE(holds(not_drawn, score(30, 1, 1)));
}

TEST(ScreenSizes, HoldsRelativeToTheAssetAsDrawn) {
  const HoldBar bar;  // 2 dB, 0.1 soft IoU, 0.3 coverage, at least 0.5
  const Scores asset = score(25, 0.8, 1.2);
  EXPECT_TRUE(holds(score(23.0, 0.7, 0.7), asset, bar));   // at every bound: coverage floor is min(1.2, 1) - 0.3
  EXPECT_FALSE(holds(score(22.9, 0.7, 0.7), asset, bar));  // PSNR 2.1 dB below
  EXPECT_FALSE(holds(score(23.0, 0.69, 0.7), asset, bar)); // soft IoU 0.11 below
  EXPECT_FALSE(holds(score(23.0, 0.7, 0.69), asset, bar)); // coverage under 0.7
  // Better than the asset is holding too (foliage the asset itself loses in its mipmaps).
  EXPECT_TRUE(holds(score(27, 0.95, 1.0), score(20, 0.3, 0.4), bar));
}

// max_screen_pixels is the largest size at which the file holds, holds_from_pixels the end of the
// run below it: never a size where it does not hold, and holds_from <= max.
TEST(ScreenSizes, WindowIsTheLargestHoldingSizeAndTheRunBelow) {
  const ScreenWindow w = holding_window(kSizes, curve({25, 27, 23, 12}, {0.7, 0.85, 0.75, 0.2}, {0.9, 0.9, 0.9, 0.3}), kAsset);
  EXPECT_EQ(w.max_pixels, 64);  // at 128 px 25 dB is more than 2 dB below the asset's 30
  EXPECT_EQ(w.min_pixels, 32);  // at 16 px 12 dB against 22
}

TEST(ScreenSizes, AFileThatHoldsNowhereClaimsNoSize) {
  const ScreenWindow w = holding_window(kSizes, curve({10, 10, 10, 10}, {0.1, 0.1, 0.1, 0.1}, {0.1, 0.1, 0.1, 0.1}), kAsset);
  EXPECT_EQ(w.max_pixels, 0);
  EXPECT_EQ(w.min_pixels, 0);
}

// The asset (200 bytes would be a tiny prop; 10,000 here), a mesh LOD and an impostor level at
// 64, 32 and 16 px.
Measurements two_files() {
  Measurements m;
  m.sizes = {64, 32, 16};
  m.views = 4;
  m.truth = 2;
  m.asset = {"in.glb", "asset", 10000, curve({30, 28, 26}, {0.95, 0.9, 0.8}, {1, 0.95, 0.9})};
  m.files = {{"big.glb", "mesh_lod", 4000, curve({29, 27, 20}, {0.95, 0.9, 0.5}, {1, 1, 0.6})},
             {"small.glb", "impostor_level", 1000, curve({20, 26, 25}, {0.6, 0.85, 0.8}, {0.8, 0.9, 0.9})}};
  return m;
}

TEST(Chain, StartsAtTheAssetThenTheSmallestFileThatHolds) {
  const nlohmann::json c = recommend_chain(two_files(), 1.0);
  ASSERT_EQ(c["chain"].size(), 3u) << c.dump(1);
  EXPECT_EQ(c["chain"][0]["kind"], "asset");
  EXPECT_TRUE(c["chain"][0]["max_pixels"].is_null());
  EXPECT_EQ(c["chain"][0]["min_pixels"], 64);
  EXPECT_EQ(c["chain"][1]["file"], "big.glb");  // small.glb does not hold at 64 px (20 < 27)
  EXPECT_EQ(c["chain"][1]["max_pixels"], 64);
  EXPECT_EQ(c["chain"][1]["min_pixels"], 32);
  EXPECT_EQ(c["chain"][2]["file"], "small.glb");
  EXPECT_EQ(c["chain"][2]["min_pixels"], 0);
  EXPECT_TRUE(c["chain"][2]["switch_distance"].is_null());
  EXPECT_DOUBLE_EQ(c["chain"][2]["error"]["psnr"].get<double>(), 26.0);
  EXPECT_EQ(c["measured"][0]["max_screen_pixels"], 64);
  EXPECT_EQ(c["measured"][1]["max_screen_pixels"], 32);
  EXPECT_EQ(c["measured"][1]["holds_from_pixels"], 16);
}

// Where no derived file holds, the asset itself; where the asset costs more than the nearer
// band's file, the best file per byte, below the bar, with the reason.
TEST(Chain, WhereNothingHoldsTheAssetOrTheReason) {
  Measurements m = two_files();
  m.files[1].at_size[2] = score(10, 0.1, 0.2);  // small.glb fails at 16 px too
  const nlohmann::json c = recommend_chain(m, 1.0);
  const nlohmann::json& last = c["chain"].back();
  EXPECT_EQ(last["file"], "small.glb");
  EXPECT_FALSE(last["bar_met"].get<bool>());
  EXPECT_NE(last["reason"].get<std::string>().find("the asset itself (10000 bytes) would"), std::string::npos) << last.dump();
  // Nothing holds at any size: the asset throughout, one entry.
  for (FileScores& f : m.files)
    for (Scores& s : f.at_size) s = score(5, 0.1, 0.1);
  const nlohmann::json a = recommend_chain(m, 1.0);
  ASSERT_EQ(a["chain"].size(), 1u);
  EXPECT_EQ(a["chain"][0]["kind"], "asset");
  EXPECT_EQ(a["chain"][0]["min_pixels"], 0);
  EXPECT_EQ(a["measured"][0]["max_screen_pixels"], 0);
}

// A file larger than the asset that draws no better is no candidate (a 12-triangle cube's 1.5 MB
// levels); one that draws better (foliage the asset loses in its mipmaps) is.
TEST(Chain, AFileLargerThanTheAssetServesOnlyWhereItDrawsBetter) {
  Measurements m = two_files();
  m.asset.bytes = 500;
  const nlohmann::json c = recommend_chain(m, 1.0);
  ASSERT_EQ(c["chain"].size(), 1u) << c.dump(1);
  EXPECT_EQ(c["chain"][0]["kind"], "asset");
  EXPECT_TRUE(c["measured"][0].contains("not_a_candidate"));
  m.files[1].at_size[2] = score(27, 0.85, 0.9);  // better than the asset's 26 dB at 16 px
  const nlohmann::json d = recommend_chain(m, 1.0);
  EXPECT_EQ(d["chain"].back()["file"], "small.glb");
  EXPECT_EQ(d["chain"].back()["max_pixels"], 16);
  EXPECT_FALSE(d["measured"][1].contains("not_a_candidate"));
}

TEST(Chain, SwitchDistanceIsWhereTheObjectSpansThePixels) {
  // D x H / (2 tan(fov / 2) x pixels): 1 x 1080 / (2 tan 30 deg x 32).
  EXPECT_NEAR(distance_for_pixels(1.0, 32, 1080, 60), 1080 / (2 * std::tan(3.14159265358979 / 6) * 32), 1e-9);
  EXPECT_TRUE(recommend_chain(Measurements{}, 1.0).is_null());
  const nlohmann::json c = recommend_chain(two_files(), 2.0);
  EXPECT_NEAR(c["chain"][0]["switch_distance"].get<double>(), distance_for_pixels(2.0, 64, 1080, 60), 1e-3);
}

}  // namespace
}  // namespace qf
