// Honest screen sizes from measured looks (issue 31 item 5).
#include "pipeline/screen_sizes.h"

#include <algorithm>
#include <cassert>

namespace qf {

ScreenWindow holding_window(const std::vector<int>& sizes, const std::vector<Scores>& at_size, const HoldBar& bar) {
  assert(!sizes.empty() && sizes.size() == at_size.size() && "a score per size");
  // 1. The best look over the ladder: the highest PSNR (the larger size on a tie: it is the one
  // drawn nearer), with its IoU.
  std::size_t best = 0;
  for (std::size_t i = 0; i < at_size.size(); ++i)
    if (at_size[i].psnr > at_size[best].psnr) best = i;
  auto holds = [&](std::size_t i) {
    return at_size[i].psnr >= at_size[best].psnr - bar.psnr_drop && at_size[i].iou >= at_size[best].iou - bar.iou_drop;
  };
  // 2. The run of sizes around it that hold: towards larger sizes (smaller index), then smaller.
  std::size_t first = best, last = best;
  while (first > 0 && holds(first - 1)) --first;
  while (last + 1 < sizes.size() && holds(last + 1)) ++last;
  return {sizes[first], sizes[last], first == 0, last + 1 == sizes.size()};
}

std::vector<double> honest_screen_pixels(const std::vector<double>& geometric, const std::vector<ScreenWindow>& windows) {
  assert(geometric.size() == windows.size());
  std::vector<double> out;
  for (std::size_t i = 0; i < windows.size(); ++i) {
    double v = windows[i].max_pixels;
    if (windows[i].holds_at_largest) v = std::max(v, geometric[i]);
    // Below the finer level's value: a power-of-two step of the ladder under it.
    if (!out.empty())
      while (v >= out.back() && v >= 1) v /= 2;
    out.push_back(v);
  }
  return out;
}

}  // namespace qf
