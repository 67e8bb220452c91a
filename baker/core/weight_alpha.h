// How an impostor atlas stores a basis function's weight w in alpha: 1 - (1 - w)^e, the
// QF_impostor_level extension's alphaExponent (e = 1 stores w itself). The baker writes it
// (primitives/texture, TextureOptions::alpha_exponent); a runtime that blends the weights, as the
// paper's method does, inverts it (runtime_gl/loader).
#pragma once

#include <algorithm>
#include <cmath>

namespace qf {

inline double encode_alpha(double weight, double exponent) {
  return 1.0 - std::pow(1.0 - std::clamp(weight, 0.0, 1.0), exponent);
}

inline double decode_alpha(double alpha, double exponent) {
  return 1.0 - std::pow(1.0 - std::clamp(alpha, 0.0, 1.0), 1.0 / exponent);
}

}  // namespace qf
