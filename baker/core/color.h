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

inline std::uint8_t linear_to_srgb8(double l) {
  l = std::clamp(l, 0.0, 1.0);
  const double v = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(v * 255));
}

}  // namespace qf
