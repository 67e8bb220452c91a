// Mipmaps on the CPU: GL 1.1 has no mipmap generation, so draw_gl11 uploads every level itself.
// Plain CPU code, unit-tested without GL.
#pragma once

#include <vector>

#include "runtime_gl/scene.h"

namespace qf::render {

// The mip chain of `base`: the levels it carries (Image::mips, a KTX2 file's), else made by 2x2
// box filtering (rounded to nearest; an odd last row or column is repeated), down to 1x1; element
// 0 is `base`. With `premultiply` the texels are premultiplied by alpha (before filtering), which
// additive blending needs and which filters correctly.
std::vector<Image> mip_chain(const Image& base, bool premultiply);

}  // namespace qf::render
