// The recommended chain: the cheapest good file per screen-size band, from the measurements.
#include "pipeline/chain.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/types.h"

namespace qf {
namespace {

double rounded(double v, double step) { return canonical_double(static_cast<float>(std::round(v / step) * step)); }

// 1. A band's choice among the files of at most `cap` bytes (the nearer band's choice: farther away
// never costs more): the fewest bytes that reach the quality bar there (PSNR and IoU, as the
// manifest rounds them, so that it can be checked from the manifest); where none does, the best
// trade, PSNR less 1 dB per doubling of bytes (the highest PSNR alone took the spider's 933 KB
// impostor level over its 39 KB mesh LOD for 2.2 dB; drawn at 96 px the two look alike). The
// earlier candidate on a tie.
double trade(const FileScores& c, std::size_t band) {
  return rounded(c.at_size[band].psnr, 0.01) - std::log2(static_cast<double>(std::max<std::size_t>(1, c.bytes)));
}

bool meets_bar(const FileScores& f, std::size_t band, const ChainRule& o) {
  return rounded(f.at_size[band].psnr, 0.01) >= o.min_psnr && rounded(f.at_size[band].iou, 0.001) >= o.min_iou;
}

// Among `allowed` files: the smallest that meets the bar, else the best trade; files.size() when
// none is allowed.
std::size_t choose_among(const std::vector<FileScores>& files, std::size_t band, const std::vector<bool>& allowed, const ChainRule& o) {
  std::size_t pick = files.size(), best = files.size();
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!allowed[i]) continue;
    if (best == files.size() || trade(files[i], band) > trade(files[best], band)) best = i;
    if (meets_bar(files[i], band, o) && (pick == files.size() || files[i].bytes < files[pick].bytes)) pick = i;
  }
  return pick < files.size() ? pick : best;
}

// The files valid at the band's size and within the byte cap; without one, the valid ones; without
// those (a band above every file's size), the files made for the largest sizes. Only files drawn
// at the band's size (Scores::measured) take part.
std::size_t choose(const Measurements& m, std::size_t band, std::size_t cap, const std::vector<double>& max_pixels, const ChainRule& o) {
  const std::size_t n = m.files.size();
  const auto limit = [&](std::size_t i) { return i < max_pixels.size() && max_pixels[i] > 0 ? kShownAbove * max_pixels[i] : 0.0; };
  const auto drawn = [&](std::size_t i) { return m.files[i].at_size[band].measured; };
  double largest = 0;
  std::vector<bool> valid(n), capped(n), largest_made(n);
  for (std::size_t i = 0; i < n; ++i) {
    valid[i] = drawn(i) && (limit(i) == 0 || m.sizes[band] <= limit(i));
    capped[i] = valid[i] && m.files[i].bytes <= cap;
    if (drawn(i)) largest = std::max(largest, limit(i));
  }
  for (std::size_t i = 0; i < n; ++i) largest_made[i] = drawn(i) && limit(i) == largest;
  for (const std::vector<bool>* allowed : {&capped, &valid, &largest_made}) {
    const std::size_t pick = choose_among(m.files, band, *allowed, o);
    if (pick < n) return pick;
  }
  return 0;
}

// 2. The chain, nearest first: one entry per run of bands with the same file, shown from the
// object's on-screen size max_pixels (null: any larger) down to min_pixels (0: any smaller), that
// is out to switch_distance (null: the last entry).
nlohmann::json chain_entries(const Measurements& m, double diagonal, const std::vector<double>& max_pixels, const ChainRule& o) {
  nlohmann::json chain = nlohmann::json::array();
  for (std::size_t band = 0; band < m.sizes.size(); ++band) {
    const std::size_t cap = chain.empty() ? std::numeric_limits<std::size_t>::max() : chain.back()["bytes"].get<std::size_t>();
    const FileScores& c = m.files[choose(m, band, cap, max_pixels, o)];
    const int min_pixels = band + 1 < m.sizes.size() ? m.sizes[band + 1] : 0;
    const nlohmann::json far = min_pixels > 0 ? nlohmann::json(rounded(distance_for_pixels(diagonal, min_pixels, o.screen_height, o.fov_degrees), 1e-4))
                                              : nlohmann::json(nullptr);
    if (!chain.empty() && chain.back()["file"] == c.file) {
      chain.back()["min_pixels"] = min_pixels;
      chain.back()["switch_distance"] = far;
      continue;
    }
    chain.push_back({{"file", c.file},
                     {"kind", c.kind},
                     {"bytes", c.bytes},
                     {"max_pixels", band == 0 ? nlohmann::json(nullptr) : nlohmann::json(m.sizes[band])},
                     {"min_pixels", min_pixels},
                     {"switch_distance", far},
                     {"measured_at_pixels", m.sizes[band]},
                     {"error", scores_entry(c.at_size[band])},
                     {"bar_met", meets_bar(c, band, o)}});
  }
  return chain;
}

}  // namespace

nlohmann::json scores_entry(const Scores& s) {
  return {{"psnr", rounded(s.psnr, 0.01)}, {"iou", rounded(s.iou, 0.001)}, {"soft_iou", rounded(s.soft_iou, 0.001)}};
}

double distance_for_pixels(double diagonal, double pixels, double screen_height, double fov_degrees) {
  return diagonal * screen_height / (2 * std::tan(0.5 * fov_degrees * 3.14159265358979323846 / 180) * pixels);
}

nlohmann::json recommend_chain(const Measurements& m, double diagonal, const ChainRule& o, const std::vector<double>& max_pixels) {
  if (m.files.empty() || m.sizes.empty()) return nullptr;
  nlohmann::json measured = nlohmann::json::array();
  for (const FileScores& c : m.files) {
    nlohmann::json at = nlohmann::json::array();
    for (const Scores& s : c.at_size) at.push_back(s.measured ? scores_entry(s) : nlohmann::json(nullptr));
    nlohmann::json e{{"file", c.file}, {"kind", c.kind}, {"bytes", c.bytes}, {"at_pixels", at}};
    const std::size_t i = measured.size();
    e["max_screen_pixels"] = i < max_pixels.size() && max_pixels[i] > 0 ? nlohmann::json(max_pixels[i]) : nlohmann::json(nullptr);
    measured.push_back(e);
  }
  return {{"rule", "per band, nearest first, among files valid at the band's size (at most shown_above x their max_screen_pixels) and "
                   "no larger than the nearer band's: the smallest with PSNR >= min_psnr and IoU >= min_iou (else the highest PSNR - "
                   "log2(bytes); bar_met false), drawn by the engine method at the band's largest size from `views` directions (a file "
                   "only at sizes where it is valid, null elsewhere; impostor levels at every size) against the truth (the input drawn once per view at `truth` x the largest size, box-filtered down)"},
          {"sizes", m.sizes},
          {"views", m.views},
          {"truth", m.truth},
          {"min_psnr", rounded(o.min_psnr, 0.01)},
          {"min_iou", rounded(o.min_iou, 0.001)},
          {"shown_above", kShownAbove},
          {"screen_height", o.screen_height},
          {"fov_degrees", rounded(o.fov_degrees, 0.01)},
          {"chain", chain_entries(m, diagonal, max_pixels, o)},
          {"measured", measured}};
}

}  // namespace qf
