// The fidelity metric on hand-made frames (no GL): a picture that draws nothing, or two empty
// pictures, never passes for a match (issue 48), and coverage says how much of the truth is drawn.
#include <gtest/gtest.h>

#include <cmath>

#include "measure/any_scene.h"
#include "measure/image_metrics.h"

namespace qf::render {
namespace {

constexpr int kSide = 32;
const Rgb8 kGrey{128, 128, 128};

// A frame pair (over black, over white) of a `colour` drawn at coverage `cover(x, y)`.
template <typename Cover>
RenderPair frame(Rgb8 colour, Cover cover) {
  RenderPair p;
  for (Image* im : {&p.over_black, &p.over_white}) im->width = im->height = kSide, im->rgba.assign(kSide * kSide * 4, 255);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const double a = cover(x, y);
      const std::size_t i = (std::size_t(y) * kSide + std::size_t(x)) * 4;
      const int rgb[3] = {colour.r, colour.g, colour.b};
      for (int k = 0; k < 3; ++k) {
        p.over_black.rgba[i + k] = static_cast<std::uint8_t>(std::lround(a * rgb[k]));
        p.over_white.rgba[i + k] = static_cast<std::uint8_t>(std::lround(a * rgb[k] + (1 - a) * 255));
      }
    }
  return p;
}
RenderPair empty() { return frame({0, 0, 0}, [](int, int) { return 0.0; }); }

TEST(Metrics, TwoEmptyPicturesAreNoEvidence) {
  const ViewMetrics m = compare_renders(empty(), empty(), kGrey);
  EXPECT_FALSE(has_evidence(m));
  EXPECT_TRUE(std::isnan(m.iou));
  EXPECT_TRUE(std::isnan(m.psnr));
  EXPECT_TRUE(std::isnan(m.coverage));
}

// A beam a quarter of a pixel wide: its silhouette (coverage >= 0.5) is empty in both pictures, and
// a picture that draws nothing keeps a high PSNR over the footprint (the faint pixels differ
// little); coverage 0 is what shows it drew nothing.
TEST(Metrics, AThinPartDrawnByNothingHasCoverageZero) {
  const RenderPair beam = frame({60, 60, 60}, [](int x, int) { return x == 10 ? 0.25 : 0.0; });
  const ViewMetrics none = compare_renders(beam, empty(), kGrey);
  EXPECT_TRUE(has_evidence(none));
  EXPECT_TRUE(std::isnan(none.iou)) << "two empty silhouettes";
  EXPECT_GT(none.psnr, 20.0);
  EXPECT_NEAR(none.coverage, 0.0, 1e-3);
  const ViewMetrics same = compare_renders(beam, beam, kGrey);
  EXPECT_NEAR(same.coverage, 1.0, 0.01);
  EXPECT_EQ(same.psnr, 99.0);
  EXPECT_NEAR(same.soft_iou, 1.0, 0.01);
  // Drawn solid a pixel wide: four times the coverage, soft IoU a quarter.
  const ViewMetrics thick = compare_renders(beam, frame({60, 60, 60}, [](int x, int) { return x == 10 ? 1.0 : 0.0; }), kGrey);
  EXPECT_NEAR(thick.coverage, 4.0, 0.1);
  EXPECT_NEAR(thick.soft_iou, 0.25, 0.02);
  EXPECT_NEAR(thick.iou, 0.0, 1e-9);
}

// The mean over views: a view without evidence adds nothing; coverage is the summed ratio.
TEST(Metrics, MeanOverViewsSkipsViewsWithoutEvidence) {
  const RenderPair half = frame({200, 50, 50}, [](int x, int) { return x < kSide / 2 ? 1.0 : 0.0; });
  const ViewMetrics a = compare_renders(half, half, kGrey), b = compare_renders(empty(), empty(), kGrey);
  const ViewMetrics m = mean_of({a, b});
  EXPECT_EQ(m.psnr, 99.0);
  EXPECT_NEAR(m.iou, 1.0, 1e-9);
  EXPECT_NEAR(m.coverage, 1.0, 1e-6);
  EXPECT_TRUE(std::isnan(mean_of({b, b}).psnr));
}

}  // namespace
}  // namespace qf::render
