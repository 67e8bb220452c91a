// Honest screen sizes: the on-screen sizes at which a file's measured look holds, judged against
// the asset itself as an engine draws it at the same size, and the ladder of sizes measured.
#pragma once

#include <vector>

#include "measure/measurements.h"

namespace qf {

// A file holds at a size when it looks there about as good as the asset as drawn at that size:
// its footprint PSNR at most `psnr_drop` below the asset's, its soft IoU at most `soft_iou_drop`
// below, its coverage at most `coverage_drop` below the asset's (taken as 1 where the asset covers
// more than the truth), and never under `min_coverage` (half of what the truth covers: a level
// that draws nothing scores a fine PSNR on a frame of background, but covers 0). A size without
// evidence (the truth covers under half a pixel) holds for no file. Issue 48's bounds are 3 dB and
// half the coverage, judged from 8 views against a 4x truth; the bake measures from 4 views
// (--measure-views) against a 2x truth, so the PSNR bound keeps 1 dB for that: 2CylinderEngine's
// 63-quad level at 32 px was 2.24 dB below the asset by the bake's figures and 3.13 dB by 8 views
// (scripts/bench.sh holds).
struct HoldBar {
  double psnr_drop = 2.0;
  double soft_iou_drop = 0.1;
  double coverage_drop = 0.3;
  double min_coverage = 0.5;
};

// A figure as the manifest writes it: to `step` (0.01 dB, 0.001 for the ratios), through float as
// every JSON figure of the project (core/types.h canonical_double). The rule compares these, so
// that it can be checked from the manifest alone.
double manifest_figure(double v, double step);

// Whether `file` holds where the asset as drawn scores `asset` (both at one size).
bool holds(const Scores& file, const Scores& asset, const HoldBar& bar = {});

// Where a file holds, on `sizes` (largest first; `file` and `asset` one score per size).
struct ScreenWindow {
  int max_pixels = 0;  // the largest size at which it holds (0: none, it is made for no size)
  int min_pixels = 0;  // the smallest of the run of sizes from there down at which it holds
};
ScreenWindow holding_window(const std::vector<int>& sizes, const std::vector<Scores>& file, const std::vector<Scores>& asset,
                            const HoldBar& bar = {});

// The largest on-screen size measured, pixels (measure/measure.h: every file at 256 px and below,
// then doubling while a file holds): no file is shown above it (the asset itself is), so none
// needs texels for more.
constexpr int kLargestMeasuredPixels = 1024;

}  // namespace qf
