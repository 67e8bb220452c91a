// sRGB bytes <-> linear 16-bit values: glTF vertex colours (COLOR_0) are linear, our colours are
// the files' sRGB bytes. 16 bits so that the round trip gives back every byte (8 would band darks).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace qf {

inline std::uint16_t srgb_to_linear16(std::uint8_t c) {
  const double v = c / 255.0;
  const double l = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  return static_cast<std::uint16_t>(std::lround(l * 65535));
}

inline std::uint8_t linear16_to_srgb(std::uint16_t c) {
  const double l = c / 65535.0;
  const double v = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
}

// Float forms for colour arithmetic in linear light (texture filtering, material factors).
inline float srgb8_to_linear(std::uint8_t c) {
  static const auto table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double v = i / 255.0;
      t[static_cast<std::size_t>(i)] = static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table[c];
}

// The sRGB byte of a linear value by the formula (IEC 61966-2-1), clamped to 0..1: the definition
// linear_to_srgb8 must give bit for bit.
inline std::uint8_t linear_to_srgb8_formula(double l) {
  l = std::clamp(l, 0.0, 1.0);
  const double v = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(v * 255));
}

namespace detail {

// linear_to_srgb8's tables. thresholds[k] (k = 1..255): the least double in (0, 1) the formula
// takes to byte k or more (bisection over doubles), with -inf and +inf at 0 and 256. The sRGB
// value rises with l at a slope of at least 0.44 (its slope at l = 1), so an l more than kMargin
// from every threshold is at least 255 x 0.44 x 1e-9 = 1e-7 of a byte from a rounding boundary,
// far beyond pow's error (an ulp or two): there the tables' byte is the formula's; nearer, the
// formula decides. bucket[i]: the formula's byte at l = i / kBuckets; a bucket (1/4096 wide)
// holds at most one threshold, as thresholds lie at least 1 / (255 x 12.92) = 3.0e-4 apart (the
// linear segment is the steepest part). clean[i]: the bucket's byte when no threshold lies within
// kMargin of it (94% of them, the answer without a comparison), else kMixed.
struct SrgbTables {
  static constexpr int kBuckets = 4096;
  static constexpr double kMargin = 1e-9;
  static constexpr std::uint16_t kMixed = 256;
  std::array<double, 257> thresholds{};
  std::array<std::uint8_t, kBuckets + 1> bucket{};
  std::array<std::uint16_t, kBuckets> clean{};
  SrgbTables() {
    thresholds[0] = -INFINITY;
    thresholds[256] = INFINITY;
    for (int k = 1; k < 256; ++k) {
      double lo = 0, hi = 1;  // formula(lo) < k <= formula(hi)
      for (;;) {
        const double mid = lo + (hi - lo) / 2;
        if (mid <= lo || mid >= hi) break;
        (linear_to_srgb8_formula(mid) >= k ? hi : lo) = mid;
      }
      thresholds[static_cast<std::size_t>(k)] = hi;
    }
    for (int i = 0; i <= kBuckets; ++i) bucket[static_cast<std::size_t>(i)] = linear_to_srgb8_formula(double(i) / kBuckets);
    for (int i = 0; i < kBuckets; ++i) {
      const double lo = double(i) / kBuckets - kMargin, hi = double(i + 1) / kBuckets + kMargin;
      bool mixed = false;
      for (int k = 1; k < 256; ++k) mixed = mixed || (thresholds[static_cast<std::size_t>(k)] >= lo && thresholds[static_cast<std::size_t>(k)] <= hi);
      clean[static_cast<std::size_t>(i)] = mixed ? kMixed : bucket[static_cast<std::size_t>(i)];
    }
  }
};

inline const SrgbTables& srgb_tables() {
  static const SrgbTables t;
  return t;
}

}  // namespace detail

// linear_to_srgb8_formula without its pow (the colour of every textured sample point): a table
// lookup, the formula itself near a byte's rounding boundary and outside (0, 1).
inline std::uint8_t linear_to_srgb8(double l) {
  if (!(l > 0.0 && l < 1.0)) return linear_to_srgb8_formula(l);  // also NaN
  const detail::SrgbTables& t = detail::srgb_tables();
  const int i = static_cast<int>(l * detail::SrgbTables::kBuckets);
  if (t.clean[static_cast<std::size_t>(i)] != detail::SrgbTables::kMixed) return static_cast<std::uint8_t>(t.clean[static_cast<std::size_t>(i)]);
  std::size_t b = t.bucket[static_cast<std::size_t>(i)];
  if (l >= t.thresholds[b + 1]) ++b;
  if (l - t.thresholds[b] < detail::SrgbTables::kMargin || t.thresholds[b + 1] - l < detail::SrgbTables::kMargin)
    return linear_to_srgb8_formula(l);
  return static_cast<std::uint8_t>(b);
}

}  // namespace qf
