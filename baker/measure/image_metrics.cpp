// The metrics and image arithmetic (see image_metrics.h). One plain loop over the pixels: through
// OpenImageIO's float images and pixel iterators they took a fifth of a mesh bake's CPU (bunny00
// with the chain). Thresholds are steep clamps (c >= t  <=>  clamp((c - t) * 1e6 + 1, 0, 1)).
#include "measure/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace qf::render {
namespace {

// Under half a pixel of the truth's coverage there is nothing to judge a picture by.
constexpr double kEvidencePixels = 0.5;

// 1 where c >= t, else 0, with a ramp of 1e-6 below t (the metrics' thresholds).
float at_least(float c, float t) { return std::clamp((c - t) * 1e6f + 1.0f, 0.0f, 1.0f); }

// One pixel of a pair: coverage c = 1 - mean over RGB of (W - B), and the colour over `bg`,
// B + (W - B) * bg, each channel 0..1.
struct Covered {
  float c;
  float rgb[3];
};
Covered covered(const RenderPair& r, std::size_t i, const float bg[3]) {
  Covered out{1, {}};
  for (std::size_t k = 0; k < 3; ++k) {
    const float b = r.over_black.rgba[i + k] / 255.0f, open = r.over_white.rgba[i + k] / 255.0f - b;
    out.c -= open / 3;
    out.rgb[k] = b + open * bg[k];
  }
  return out;
}

}  // namespace

bool has_evidence(const ViewMetrics& m) { return m.covered_reference >= kEvidencePixels; }

ViewMetrics compare_renders(const RenderPair& reference, const RenderPair& impostor, Rgb8 background, std::vector<float>* diff) {
  const float bg[3] = {background.r / 255.0f, background.g / 255.0f, background.b / 255.0f};
  const Image& ref = reference.over_black;
  if (ref.width != impostor.over_black.width || ref.height != impostor.over_black.height)
    throw std::logic_error("compare_renders: the two renders differ in size");
  const std::size_t pixels = static_cast<std::size_t>(ref.width) * static_cast<std::size_t>(ref.height);
  if (diff) diff->resize(pixels * 3);
  // One pass over the pixels (sums in double): the counts of covered pixels (c >= 0.5), the
  // colour differences weighted by the footprint max(c_ref, c), fractional coverage, brightness.
  double n_either = 0, n_ref = 0, n_both = 0, n_imp = 0, n_solid_both = 0, weight = 0, sum = 0, sum2 = 0, soft_min = 0, soft_max = 0,
         bright_i = 0, bright_r = 0, cover_r = 0, cover_i = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    const Covered r = covered(reference, p * 4, bg), m = covered(impostor, p * 4, bg);
    const float in_r = at_least(r.c, 0.5f), in_i = at_least(m.c, 0.5f), either = std::max(in_r, in_i);
    n_either += either, n_ref += in_r, n_imp += in_i, n_both += in_r * in_i, n_solid_both += in_r * at_least(m.c, 0.9f);
    const float cr = std::clamp(r.c, 0.0f, 1.0f), ci = std::clamp(m.c, 0.0f, 1.0f), w = std::max(cr, ci);
    weight += w;
    for (std::size_t k = 0; k < 3; ++k) {
      const float d = std::abs(r.rgb[k] - m.rgb[k]);
      sum += static_cast<double>(d) * w, sum2 += static_cast<double>(d) * d * w;
      bright_i += m.rgb[k] * in_i, bright_r += r.rgb[k] * in_r;
      if (diff) (*diff)[p * 3 + k] = d;
    }
    soft_min += std::min(cr, ci), soft_max += w, cover_r += cr, cover_i += ci;
  }
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  ViewMetrics m;
  m.covered = static_cast<std::size_t>(n_ref);
  m.covered_reference = cover_r, m.covered_image = cover_i;
  const bool evidence = cover_r >= kEvidencePixels;
  m.iou = n_either > 0 ? n_both / n_either : kNone;
  m.soft_iou = evidence ? soft_min / soft_max : kNone;
  m.coverage = evidence ? cover_i / cover_r : kNone;
  m.mae = weight > 0 ? sum / (3 * weight) : 0.0;
  const double mse = weight > 0 ? sum2 / (3 * weight) : 0.0;
  m.psnr = !evidence ? kNone : mse > 0 ? std::min(99.0, 10 * std::log10(1.0 / mse)) : 99.0;
  // Mean grey (0..255, the mean of R, G, B) over each image's own covered pixels.
  if (n_imp > 0) m.brightness = 255 * bright_i / (3 * n_imp);
  if (n_ref > 0) m.reference_brightness = 255 * bright_r / (3 * n_ref);
  if (n_ref > 0) {
    m.holes = (n_ref - n_both) / n_ref;
    m.see_through = (n_both - n_solid_both) / n_ref;
  }
  return m;
}

Image to_8bit(const std::vector<float>& rgb, int width, int height, float gain) {
  Image out;
  out.width = width;
  out.height = height;
  out.rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 255);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      out.rgba[i * 4 + c] = static_cast<std::uint8_t>(std::clamp(rgb[i * 3 + c] * gain, 0.0f, 1.0f) * 255 + 0.5f);
  return out;
}

// A plain loop: OIIO's resize (a general filter through pixel iterators) took 27% of a mesh bake
// with its recommended chain, most of the chain's time.
Image box_downsample(const Image& image, int factor) {
  if (factor <= 1) return image;
  const std::size_t f = static_cast<std::size_t>(factor), in_w = static_cast<std::size_t>(image.width);
  Image out{image.width / factor, image.height / factor, {}};
  const std::size_t w = static_cast<std::size_t>(out.width), h = static_cast<std::size_t>(out.height);
  std::vector<std::uint32_t> sums(w * 4);
  out.rgba.resize(w * h * 4);
  for (std::size_t y = 0; y < h; ++y) {
    std::fill(sums.begin(), sums.end(), 0u);
    for (std::size_t j = 0; j < f; ++j) {
      const std::uint8_t* row = image.rgba.data() + (y * f + j) * in_w * 4;
      for (std::size_t x = 0; x < w * f; ++x)
        for (std::size_t c = 0; c < 4; ++c) sums[(x / f) * 4 + c] += row[x * 4 + c];
    }
    for (std::size_t i = 0; i < w * 4; ++i) out.rgba[y * w * 4 + i] = static_cast<std::uint8_t>((sums[i] + f * f / 2) / (f * f));
  }
  return out;
}

}  // namespace qf::render
