// sRGB bytes <-> linear 16-bit values: glTF vertex colours (COLOR_0) are linear, our colours are
// the files' sRGB bytes. 16 bits so that the round trip gives back every byte (8 would band darks).
#pragma once

#include <algorithm>
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

}  // namespace qf
