// The recommended chain: the asset itself near, then the cheapest file that holds per screen-size
// band, from the measurements.
#include "measure/chain.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/types.h"

namespace qf {
namespace {

double rounded(double v, double step) { return manifest_figure(v, step); }
nlohmann::json figure(double v, double step) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(rounded(v, step)); }

// A file larger than the asset is worth its bytes only where it draws better than the asset.
bool draws_better(const Scores& f, const Scores& asset) {
  return f.evidence() && asset.evidence() && (f.psnr > asset.psnr || f.soft_iou > asset.soft_iou);
}

// One band's choice: the derived file (index into m.files) or the asset (m.files.size()), and why.
struct Pick {
  std::size_t file = 0;
  bool bar_met = true;
  std::string reason;  // empty where a derived file holds
};

// 1. Among the derived files no larger than `cap` (a nearer derived file's bytes: farther away never
// costs more), and no larger than the asset unless they draw better: the smallest that holds.
// Else the asset itself, where it is within the cap; else, below the bar, the best trade of PSNR
// against bytes (1 dB per doubling) among those files that hold at half the size or more (never a
// file shown above twice the largest size at which it holds); else the asset itself after all.
// `largest[i]`: the largest size at which file i holds (0: none).
Pick choose(const Measurements& m, std::size_t band, std::size_t cap, const std::vector<int>& largest, const HoldBar& bar) {
  const std::size_t n = m.files.size();
  const Scores& asset = m.asset.at_size[band];
  const int size = m.sizes[band];
  std::size_t pick = n, trade = n;
  const auto trade_of = [&](std::size_t i) { return rounded(m.files[i].at_size[band].psnr, 0.01) - std::log2(double(std::max<std::size_t>(1, m.files[i].bytes))); };
  for (std::size_t i = 0; i < n; ++i) {
    const FileScores& f = m.files[i];
    const Scores& s = f.at_size[band];
    if (f.bytes > cap || (f.bytes > m.asset.bytes && !draws_better(s, asset))) continue;
    if (holds(s, asset, bar) && (pick == n || f.bytes < m.files[pick].bytes)) pick = i;
    if (s.evidence() && 2 * largest[i] >= size && (trade == n || trade_of(i) > trade_of(trade))) trade = i;
  }
  if (pick < n) return {pick, true, ""};
  const std::string at = " at " + std::to_string(size) + " px";
  if (m.asset.bytes <= cap) return {n, true, "no derived file holds" + at + ": the asset itself"};
  const std::string why = "no file within the nearer band's " + std::to_string(cap) + " bytes holds" + at;
  if (trade < n) return {trade, false, why + "; the asset itself (" + std::to_string(m.asset.bytes) + " bytes) would: the best file per byte"};
  return {n, true, why + ", nor within twice its size: the asset itself (" + std::to_string(m.asset.bytes) + " bytes)"};
}

// 2. The chain, nearest first: one entry per run of bands with the same file, shown from the
// object's on-screen size max_pixels (null: any larger) down to min_pixels (0: any smaller), that
// is out to switch_distance (null: the last entry).
nlohmann::json chain_entries(const Measurements& m, double diagonal, const ChainRule& o) {
  const std::size_t n = m.files.size();
  const auto entry = [&](std::size_t i) -> const FileScores& { return i < n ? m.files[i] : m.asset; };
  nlohmann::json chain = nlohmann::json::array();
  // Above the largest size measured: the asset itself, always (no file is judged there).
  chain.push_back({{"file", m.asset.file}, {"kind", "asset"}, {"bytes", m.asset.bytes}, {"max_pixels", nullptr}, {"min_pixels", m.sizes[0]},
                   {"switch_distance", nullptr}, {"measured_at_pixels", nullptr}, {"error", nullptr}, {"bar_met", true},
                   {"reason", "above " + std::to_string(m.sizes[0]) + " px, the largest size measured: the asset itself"}});
  std::vector<int> largest;
  for (const FileScores& f : m.files) largest.push_back(holding_window(m.sizes, f.at_size, m.asset.at_size, o.bar).max_pixels);
  std::size_t last = n;
  for (std::size_t band = 0; band < m.sizes.size(); ++band) {
    const std::size_t cap = last < n ? m.files[last].bytes : std::numeric_limits<std::size_t>::max();
    const Pick p = choose(m, band, cap, largest, o.bar);
    const int min_pixels = band + 1 < m.sizes.size() ? m.sizes[band + 1] : 0;
    if (p.file == last) {
      // One entry for the run: it met the bar only where every band of it did.
      chain.back()["min_pixels"] = min_pixels;
      if (!p.bar_met && chain.back()["bar_met"].get<bool>()) chain.back()["bar_met"] = false, chain.back()["reason"] = p.reason;
      if (chain.back()["measured_at_pixels"].is_null()) {  // the asset's first entry reaches a measured band
        chain.back()["measured_at_pixels"] = m.sizes[band];
        chain.back()["error"] = scores_entry(m.asset.at_size[band]);
        chain.back()["reason"] = p.reason;
      }
      continue;
    }
    const FileScores& c = entry(p.file);
    nlohmann::json e{{"file", c.file},
                     {"kind", c.kind},
                     {"bytes", c.bytes},
                     {"max_pixels", m.sizes[band]},
                     {"min_pixels", min_pixels},
                     {"switch_distance", nullptr},
                     {"measured_at_pixels", m.sizes[band]},
                     {"error", scores_entry(c.at_size[band])},
                     {"bar_met", p.bar_met}};
    if (!p.reason.empty()) e["reason"] = p.reason;
    chain.push_back(e);
    last = p.file;
  }
  // Switch distances: where each entry's smallest size is reached.
  for (std::size_t i = 0; i + 1 < chain.size(); ++i)
    chain[i]["switch_distance"] = rounded(distance_for_pixels(diagonal, chain[i]["min_pixels"].get<double>(), o.screen_height, o.fov_degrees), 1e-4);
  return chain;
}

nlohmann::json at_pixels(const FileScores& f) {
  nlohmann::json at = nlohmann::json::array();
  for (const Scores& s : f.at_size) at.push_back(s.measured ? scores_entry(s) : nlohmann::json(nullptr));
  return at;
}

}  // namespace

nlohmann::json scores_entry(const Scores& s) {
  return {{"psnr", figure(s.psnr, 0.01)}, {"iou", figure(s.iou, 0.001)}, {"soft_iou", figure(s.soft_iou, 0.001)}, {"coverage", figure(s.coverage, 0.001)}};
}

nlohmann::json hold_entry(const HoldBar& bar) {
  return {{"psnr_drop", rounded(bar.psnr_drop, 0.01)},
          {"soft_iou_drop", rounded(bar.soft_iou_drop, 0.001)},
          {"coverage_drop", rounded(bar.coverage_drop, 0.001)},
          {"min_coverage", rounded(bar.min_coverage, 0.001)}};
}

double distance_for_pixels(double diagonal, double pixels, double screen_height, double fov_degrees) {
  return diagonal * screen_height / (2 * std::tan(0.5 * fov_degrees * 3.14159265358979323846 / 180) * pixels);
}

nlohmann::json recommend_chain(const Measurements& m, double diagonal, const ChainRule& o) {
  if (m.sizes.empty() || m.asset.at_size.size() != m.sizes.size()) return nullptr;
  nlohmann::json measured = nlohmann::json::array();
  for (const FileScores& c : m.files) {
    const ScreenWindow w = holding_window(m.sizes, c.at_size, m.asset.at_size, o.bar);
    nlohmann::json e{{"file", c.file}, {"kind", c.kind}, {"bytes", c.bytes}, {"at_pixels", at_pixels(c)},
                     {"max_screen_pixels", w.max_pixels}, {"holds_from_pixels", w.min_pixels}};
    bool better = false;
    for (std::size_t k = 0; k < m.sizes.size(); ++k) better = better || draws_better(c.at_size[k], m.asset.at_size[k]);
    if (c.bytes > m.asset.bytes && !better) e["not_a_candidate"] = "costs more than the asset and draws no better at any size measured";
    measured.push_back(e);
  }
  return {{"rule", "nearest first: the asset itself above the largest size measured; then per band, judged at its largest size, the "
                   "smallest derived file that holds there (as good as the asset as drawn, by `hold`) and is no larger than a nearer "
                   "derived file's, nor than the asset unless it draws better there; where none holds, the asset itself, or where the "
                   "asset costs more than the nearer band's file, the highest PSNR - log2(bytes) (bar_met false, with the reason)"},
          {"sizes", m.sizes},
          {"views", m.views},
          {"truth", m.truth},
          {"hold", hold_entry(o.bar)},
          {"screen_height", o.screen_height},
          {"fov_degrees", rounded(o.fov_degrees, 0.01)},
          {"asset", {{"file", m.asset.file}, {"bytes", m.asset.bytes}, {"at_pixels", at_pixels(m.asset)}}},
          {"chain", chain_entries(m, diagonal, o)},
          {"measured", measured}};
}

}  // namespace qf
