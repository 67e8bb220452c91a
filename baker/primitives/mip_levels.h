// The mip levels a texture file carries (issue 32): a KTX2 atlas holds its whole chain, made here
// rather than by the engine, so that an alpha-tested level keeps its coverage as it shrinks.
// Engines box-filter a PNG's mips themselves: a leaf or a beam one texel wide averages with the
// empty texels around it, its alpha drops below the cutoff, and the level shows holes at a quarter
// of its size (elephant, 1380 quads at 64 px: 5.3% holes with mips, 0.1% without).
#pragma once

#include <vector>

#include "core/types.h"

namespace qf {

struct MipOptions {
  enum class Kind {
    kColor,   // RGB sRGB bytes, averaged in linear light weighted by alpha (colour of covered texels only)
    kNormal,  // RGB a tangent-space normal map (n * 0.5 + 0.5), averaged and renormalised
    kLinear,  // RGB linear bytes (occlusion, roughness, metallic), plain averages
  };
  Kind kind = Kind::kColor;
  // The material's alpha cutoff (glTF MASK: a texel shows where alpha >= cutoff): every level's
  // alpha is scaled so that its share of texels at or above the cutoff is the base level's
  // (Castano's method, "Computing alpha mipmaps", 2010). 0: alpha is plainly box-filtered.
  float alpha_cutoff = 0;
};

// The chain of `base` (RGBA8, rows top to bottom): element 0 is the base level, each next one
// half the size (at least 1) down to 1x1, by 2x2 box filtering of the level above (an odd last
// row or column is repeated). Steps: the base's texels with alpha 0 take the colour of the nearest
// texel with alpha (so no level nor bilinear filter mixes in the black of empty texels); each level
// is filtered from the one above before its alpha is scaled; alpha is scaled per level to the base
// level's coverage. Same input, same bytes.
std::vector<TextureImage> mip_levels(const TextureImage& base, const MipOptions& options = {});

// The chain's second element alone: `image` at half its size by the same steps (bleeding, box
// filtering per kind), its alpha box-filtered and not scaled. Normal maps are stored so (glb.cpp).
TextureImage half_level(const TextureImage& image, const MipOptions& options = {});

// The share of `image`'s texels a MASK material with `cutoff` shows (alpha / 255 >= cutoff, as a
// shader compares the texel's float value).
double alpha_coverage(const TextureImage& image, float cutoff);

}  // namespace qf
