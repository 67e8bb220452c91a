// Mip chains by box filtering (see mip_chain.h).
#include "runtime_gl/mip_chain.h"

#include <algorithm>
#include <cstdint>

namespace qf::render {

namespace {

void premultiply_alpha(Image& image) {
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      image.rgba[i + c] = static_cast<std::uint8_t>((image.rgba[i + c] * image.rgba[i + 3] + 127) / 255);
}

}  // namespace

std::vector<Image> mip_chain(const Image& base, bool premultiply) {
  std::vector<Image> chain{Image{base.width, base.height, base.rgba, {}}};
  if (!base.mips.empty()) {
    chain.insert(chain.end(), base.mips.begin(), base.mips.end());
    if (premultiply)
      for (Image& level : chain) premultiply_alpha(level);
    return chain;
  }
  if (premultiply) premultiply_alpha(chain[0]);
  while (chain.back().width > 1 || chain.back().height > 1) {
    const Image& a = chain.back();
    Image b;
    b.width = std::max(1, a.width / 2);
    b.height = std::max(1, a.height / 2);
    b.rgba.resize(static_cast<std::size_t>(b.width) * static_cast<std::size_t>(b.height) * 4);
    for (int y = 0; y < b.height; ++y)
      for (int x = 0; x < b.width; ++x)
        for (int c = 0; c < 4; ++c) {
          int sum = 0;
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
              const int sx = std::min(a.width - 1, 2 * x + dx), sy = std::min(a.height - 1, 2 * y + dy);
              sum += a.rgba[(static_cast<std::size_t>(sy) * static_cast<std::size_t>(a.width) + static_cast<std::size_t>(sx)) * 4 + c];
            }
          b.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(b.width) + static_cast<std::size_t>(x)) * 4 + c] =
              static_cast<std::uint8_t>((sum + 2) / 4);
        }
    chain.push_back(std::move(b));
  }
  return chain;
}

}  // namespace qf::render
