// Coverage-preserving mip levels (see mip_levels.h).
#include "primitives/mip_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>

#include "core/color.h"

namespace qf {
namespace {

// A level in float: RGB as the kind averages it (linear light, unit vectors or linear values) and
// the box-filtered alpha before any scaling (each level is filtered from the unscaled one above,
// so a scale chosen for one level does not compound down the chain).
struct FloatLevel {
  int width = 0, height = 0;
  std::vector<float> rgb, alpha;
};

std::size_t at(int x, int y, int width) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x); }

// Step 1: every texel with alpha 0 takes the colour of its nearest texel with alpha (breadth-first
// from all of those at once, 4-neighbours, in scan order: deterministic). An image without any
// alpha is left as it is.
TextureImage bleed(const TextureImage& image) {
  TextureImage out = image;
  const int w = image.width, h = image.height;
  std::vector<char> done(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < done.size(); ++i)
    if (image.rgba[4 * i + 3] > 0) done[i] = 1, queue.push_back(i);
  while (!queue.empty()) {
    const std::size_t i = queue.front();
    queue.pop_front();
    const int x = static_cast<int>(i % static_cast<std::size_t>(w)), y = static_cast<int>(i / static_cast<std::size_t>(w));
    const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
    for (int k = 0; k < 4; ++k) {
      if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
      const std::size_t n = at(nx[k], ny[k], w);
      if (done[n]) continue;
      done[n] = 1;
      std::copy_n(&out.rgba[4 * i], 3, &out.rgba[4 * n]);
      queue.push_back(n);
    }
  }
  return out;
}

FloatLevel to_float(const TextureImage& image, MipOptions::Kind kind) {
  FloatLevel f{image.width, image.height, {}, {}};
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  f.rgb.resize(3 * n);
  f.alpha.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const std::uint8_t b = image.rgba[4 * i + c];
      f.rgb[3 * i + c] = kind == MipOptions::Kind::kColor ? srgb8_to_linear(b)
                         : kind == MipOptions::Kind::kNormal ? b / 127.5f - 1.0f
                                                             : b / 255.0f;
    }
    f.alpha[i] = image.rgba[4 * i + 3] / 255.0f;
  }
  return f;
}

// Step 2: the next level by 2x2 box filtering. Colour averages weight by alpha (an empty texel's
// colour, bled or not, does not darken a covered one), falling back to the plain mean where all
// four are empty; normals are renormalised.
FloatLevel half(const FloatLevel& a, MipOptions::Kind kind) {
  FloatLevel b;
  b.width = std::max(1, a.width / 2);
  b.height = std::max(1, a.height / 2);
  const std::size_t n = static_cast<std::size_t>(b.width) * static_cast<std::size_t>(b.height);
  b.rgb.resize(3 * n);
  b.alpha.resize(n);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) {
      std::size_t src[4];
      for (int k = 0; k < 4; ++k)
        src[k] = at(std::min(a.width - 1, 2 * x + (k & 1)), std::min(a.height - 1, 2 * y + (k >> 1)), a.width);
      float alpha = 0;
      for (std::size_t s : src) alpha += a.alpha[s];
      const bool weighted = kind == MipOptions::Kind::kColor && alpha > 0;
      float rgb[3] = {0, 0, 0};
      for (std::size_t s : src)
        for (std::size_t c = 0; c < 3; ++c) rgb[c] += (weighted ? a.alpha[s] : 1.0f) * a.rgb[3 * s + c];
      const float total = weighted ? alpha : 4.0f;
      for (float& v : rgb) v /= total;
      if (kind == MipOptions::Kind::kNormal) {
        const float len = std::sqrt(rgb[0] * rgb[0] + rgb[1] * rgb[1] + rgb[2] * rgb[2]);
        if (len > 1e-6f) {
          for (float& v : rgb) v /= len;
        } else {
          rgb[0] = rgb[1] = 0, rgb[2] = 1;
        }
      }
      const std::size_t d = at(x, y, b.width);
      std::copy_n(rgb, 3, &b.rgb[3 * d]);
      b.alpha[d] = alpha / 4.0f;
    }
  return b;
}

std::uint8_t alpha_byte(float alpha, double scale) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(static_cast<double>(alpha) * scale, 0.0, 1.0) * 255.0));
}

// The least byte a shader shows at `cutoff` (byte / 255 >= cutoff in float, as it compares).
int threshold_byte(float cutoff) {
  int t = 0;
  while (t < 256 && static_cast<float>(t) / 255.0f < cutoff) ++t;
  return t;
}

std::size_t covered(const std::vector<float>& alpha, double scale, int threshold) {
  std::size_t n = 0;
  for (float a : alpha) n += alpha_byte(a, scale) >= threshold ? 1 : 0;
  return n;
}

// Step 3: the scale whose coverage is nearest `target` texels. Coverage rises with the scale, so
// bisection finds the least scale reaching the target; the one just below may come nearer.
double coverage_scale(const std::vector<float>& alpha, double target, int threshold) {
  double lo = 0, hi = 256;
  if (static_cast<double>(covered(alpha, hi, threshold)) < target) return hi;
  for (int i = 0; i < 48; ++i) {
    const double mid = 0.5 * (lo + hi);
    (static_cast<double>(covered(alpha, mid, threshold)) >= target ? hi : lo) = mid;
  }
  const double above = static_cast<double>(covered(alpha, hi, threshold)) - target;
  const double below = target - static_cast<double>(covered(alpha, lo, threshold));
  return below < above ? lo : hi;
}

TextureImage to_bytes(const FloatLevel& f, MipOptions::Kind kind, double alpha_scale) {
  TextureImage out;
  out.width = f.width;
  out.height = f.height;
  const std::size_t n = f.alpha.size();
  out.rgba.resize(4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const float v = f.rgb[3 * i + c];
      out.rgba[4 * i + c] = kind == MipOptions::Kind::kColor
                                ? linear_to_srgb8(v)
                                : static_cast<std::uint8_t>(std::lround(std::clamp(kind == MipOptions::Kind::kNormal ? v * 0.5f + 0.5f : v, 0.0f, 1.0f) * 255.0f));
    }
    out.rgba[4 * i + 3] = alpha_byte(f.alpha[i], alpha_scale);
  }
  return out;
}

}  // namespace

double alpha_coverage(const TextureImage& image, float cutoff) {
  const int threshold = threshold_byte(cutoff);
  std::size_t n = 0;
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) n += image.rgba[i] >= threshold ? 1 : 0;
  return image.rgba.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(image.rgba.size() / 4);
}

TextureImage half_level(const TextureImage& image, const MipOptions& options) {
  return to_bytes(half(to_float(bleed(image), options.kind), options.kind), options.kind, 1.0);
}

std::vector<TextureImage> mip_levels(const TextureImage& base, const MipOptions& options) {
  std::vector<TextureImage> chain{bleed(base)};
  const double base_coverage = options.alpha_cutoff > 0 ? alpha_coverage(chain[0], options.alpha_cutoff) : 0.0;
  const int threshold = threshold_byte(options.alpha_cutoff);
  FloatLevel level = to_float(chain[0], options.kind);
  while (level.width > 1 || level.height > 1) {
    level = half(level, options.kind);
    const double target = base_coverage * static_cast<double>(level.alpha.size());
    const double scale = base_coverage > 0 ? coverage_scale(level.alpha, target, threshold) : 1.0;
    chain.push_back(to_bytes(level, options.kind, scale));
  }
  return chain;
}

}  // namespace qf
