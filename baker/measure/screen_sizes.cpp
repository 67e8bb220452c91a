// Honest screen sizes from measured looks, relative to the asset as drawn (issue 48).
#include "measure/screen_sizes.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/types.h"

namespace qf {

namespace {

// Comparisons allow for float's last bit in the rounded figures.
constexpr double kSlack = 1e-6;
double rounded(double v, double step) { return manifest_figure(v, step); }

}  // namespace

double manifest_figure(double v, double step) { return canonical_double(static_cast<float>(std::round(v / step) * step)); }

bool holds(const Scores& file, const Scores& asset, const HoldBar& bar) {
  if (!file.evidence() || !asset.evidence()) return false;
  const double coverage_floor = std::max(bar.min_coverage, std::min(rounded(asset.coverage, 0.001), 1.0) - bar.coverage_drop);
  return rounded(file.coverage, 0.001) >= coverage_floor - kSlack &&
         rounded(file.psnr, 0.01) >= rounded(asset.psnr, 0.01) - bar.psnr_drop - kSlack &&
         rounded(file.soft_iou, 0.001) >= rounded(asset.soft_iou, 0.001) - bar.soft_iou_drop - kSlack;
}

ScreenWindow holding_window(const std::vector<int>& sizes, const std::vector<Scores>& file, const std::vector<Scores>& asset, const HoldBar& bar) {
  assert(sizes.size() == file.size() && sizes.size() == asset.size() && "a score per size");
  // 1. The largest size at which it holds; 2. the run of sizes below it that hold too.
  std::size_t first = 0;
  while (first < sizes.size() && !holds(file[first], asset[first], bar)) ++first;
  if (first == sizes.size()) return {};
  std::size_t last = first;
  while (last + 1 < sizes.size() && holds(file[last + 1], asset[last + 1], bar)) ++last;
  return {sizes[first], sizes[last]};
}

}  // namespace qf
