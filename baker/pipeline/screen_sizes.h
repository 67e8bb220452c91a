// Honest screen sizes: the on-screen sizes at which a level's measured look holds, in place of the
// geometric estimate (error under half a pixel), which misses lost coverage (mipmaps eating an
// alpha-tested level's texels when it is drawn small, foliage that keeps its look far above the
// size its geometric error allows).
#pragma once

#include <vector>

#include "pipeline/measurements.h"

namespace qf {

// A level holds at a size when its PSNR there is at most `psnr_drop` below its best over the
// ladder and its IoU at most `iou_drop` below its IoU at that best: the look it reaches, kept. 1 dB and 0.05
// take the knee of the measured curves (bunny00, the generated tree, a bush, 6 views: a level's
// PSNR rises while its geometry is finer than a pixel and its texels are not eaten by mipmaps,
// then falls by 1-3 dB per doubling of size).
struct HoldBar {
  double psnr_drop = 1.0;
  double iou_drop = 0.05;
};

// The run of ladder sizes around a level's best PSNR at which it holds. `sizes` largest first,
// `at_size` one per size (both non-empty, same length).
struct ScreenWindow {
  int max_pixels = 0;             // the largest size at which it holds
  int min_pixels = 0;             // the smallest
  bool holds_at_largest = false;  // it holds at sizes.front(): its true maximum may lie above
  bool holds_at_smallest = false; // it holds at sizes.back()
};
ScreenWindow holding_window(const std::vector<int>& sizes, const std::vector<Scores>& at_size, const HoldBar& bar = {});

// The levels' max_screen_pixels from their measurements. `geometric` and `windows` per level,
// finest first. A level's value is its window's largest size; where it holds at the ladder's top,
// the larger of that and its geometric value. A coarser level never gets as large a value as a
// finer one (each is shown down to the next coarser one's value, so a coarser level reaching as
// far would hide the finer one, which looks better there): it is halved until below.
std::vector<double> honest_screen_pixels(const std::vector<double>& geometric, const std::vector<ScreenWindow>& windows);

}  // namespace qf
