// Shelf packing of the primitives' textures into block-aligned tiles with edge-extended gutters.
#include "primitives/atlas.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/color.h"

namespace qf {
namespace {

// The range of channel c (Texture::channel_min order) over every tile's covered texels; min > max
// where no tile has any.
std::array<float, 2> channel_range(const std::vector<Texture>& textures, std::size_t c) {
  std::array<float, 2> r{INFINITY, -INFINITY};
  for (const Texture& t : textures) r[0] = std::min(r[0], t.channel_min[c]), r[1] = std::max(r[1], t.channel_max[c]);
  return r;
}

// Whether occlusion (0), roughness (1) or metallic (2) spans more than one step of its linear byte.
bool varies_orm(const std::vector<Texture>& textures, std::size_t c) {
  const std::array<float, 2> r = channel_range(textures, c);
  return r[0] <= r[1] && (r[1] - r[0]) * 255.0 > 1.0;
}

// Whether emissive channel c (0..2) spans more than one step of its sRGB byte.
bool varies_emissive(const std::vector<Texture>& textures, std::size_t c) {
  const std::array<float, 2> r = channel_range(textures, 3 + c);
  return r[0] <= r[1] && linear_to_srgb8(r[1]) - linear_to_srgb8(r[0]) > 1;
}

// The middle of a constant channel's range (its value: averages of one value are that value), or
// `fallback` where no texel is covered.
float constant_value(const std::vector<Texture>& textures, std::size_t c, float fallback) {
  const std::array<float, 2> r = channel_range(textures, c);
  return r[0] <= r[1] ? std::clamp(0.5f * (r[0] + r[1]), 0.0f, 1.0f) : fallback;
}

int round_up(int v, int m) { return (v + m - 1) / m * m; }

// Fills the cell at (x, y), pad_w x pad_h texels, with texture `t` placed `gutter` texels in from
// the cell's corner and its edge texels repeated over the rest of the cell. The texture's row 0 is
// its bottom row; images run top to bottom.
void blit(const std::vector<std::uint8_t>& rgba, const Texture& t, int x, int y, int pad_w, int pad_h, int gutter,
          int image_w, std::vector<std::uint8_t>& img) {
  for (int j = 0; j < pad_h; ++j)
    for (int i = 0; i < pad_w; ++i) {
      const int si = std::clamp(i - gutter, 0, t.width - 1);
      const int sj = std::clamp(j - gutter, 0, t.height - 1);
      const std::size_t src = 4 * (static_cast<std::size_t>(t.height - 1 - sj) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(si));
      const std::size_t dst = 4 * (static_cast<std::size_t>(y + j) * static_cast<std::size_t>(image_w) + static_cast<std::size_t>(x + i));
      std::copy(rgba.begin() + static_cast<std::ptrdiff_t>(src), rgba.begin() + static_cast<std::ptrdiff_t>(src) + 4,
                img.begin() + static_cast<std::ptrdiff_t>(dst));
    }
}

// Step 3: shelves, left to right, top to bottom; a full atlas opens the next one. Places every
// tile (its image, x, y, size) and returns each image's used height.
std::vector<int> place_on_shelves(const std::vector<int>& pw, const std::vector<int>& ph, const std::vector<std::size_t>& order, int width,
                                  const AtlasOptions& o, std::vector<AtlasTile>& tiles, const std::vector<Texture>& textures) {
  std::vector<int> heights;
  int x = 0, y = 0, shelf = 0;
  std::uint32_t image = 0;
  heights.push_back(0);
  for (std::size_t k : order) {
    if (x + pw[k] > width) x = 0, y += shelf, shelf = 0;
    if (y + ph[k] > o.max_side) {
      ++image, x = 0, y = 0, shelf = 0;
      heights.push_back(0);
    }
    tiles[k] = {image, x + o.gutter, y + o.gutter, textures[k].width, textures[k].height, 0, 0, 0, 0};
    x += pw[k];
    shelf = std::max(shelf, ph[k]);
    heights[image] = std::max(heights[image], y + shelf);
  }
  return heights;
}

// Channel c's texels of `images` (RGBA) set to 255: a constant channel is carried by its factor.
void saturate_channel(std::vector<std::vector<std::uint8_t>>& images, std::size_t c) {
  for (std::vector<std::uint8_t>& img : images)
    for (std::size_t k = c; k < img.size(); k += 4) img[k] = 255;
}

// Step 5: the ORM and emissive images of the channels that vary, in the colour images' layout.
void fill_channel_images(const std::vector<Texture>& textures, const std::vector<int>& pw, const std::vector<int>& ph, const AtlasOptions& o,
                         Atlas& a) {
  const LevelChannels& ch = a.channels;
  for (int which = 0; which < 2; ++which) {
    if (!(which == 0 ? ch.orm_texture : ch.emissive_texture)) continue;
    std::vector<std::vector<std::uint8_t>>& images = which == 0 ? a.orm_images : a.emissive_images;
    for (std::size_t i = 0; i < a.images.size(); ++i) images.emplace_back(a.images[i].size(), 255);
    for (std::size_t k = 0; k < textures.size(); ++k) {
      const AtlasTile& t = a.tiles[k];
      blit(which == 0 ? textures[k].orm : textures[k].emissive, textures[k], t.x - o.gutter, t.y - o.gutter, pw[k], ph[k], o.gutter,
           a.widths[t.atlas], images[t.atlas]);
    }
    // Constant channels: 255, their factor carries the value.
    if (which == 0) {
      if (!ch.occlusion_texture) saturate_channel(images, 0);
      for (std::size_t c = 1; c < 3; ++c)
        if (!varies_orm(textures, c)) saturate_channel(images, c);
    } else {
      for (std::size_t c = 0; c < 3; ++c)
        if (!varies_emissive(textures, c)) saturate_channel(images, c);
    }
  }
}

// Step 4: the images (and normal maps, when every texture has one), power-of-two high, the
// textures copied in with their gutters, and every tile's texture coordinates.
void fill_images(const std::vector<Texture>& textures, const std::vector<int>& pw, const std::vector<int>& ph, int width,
                 const std::vector<int>& heights, const AtlasOptions& o, Atlas& a) {
  const bool with_normals = !textures.empty() &&
      std::all_of(textures.begin(), textures.end(), [](const Texture& t) { return !t.normals.empty(); });
  for (std::size_t i = 0; i < heights.size(); ++i) {
    a.widths.push_back(width);
    // Power-of-two sides: mipmapping everywhere (WebGL 1 needs it), no validator NPOT notices.
    int side = o.block;
    while (side < heights[i]) side *= 2;
    a.heights.push_back(side);
    const std::size_t bytes = 4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(a.heights.back());
    a.images.emplace_back(bytes, 0);
    if (with_normals) a.normal_images.emplace_back(bytes, 0);
  }
  for (std::size_t k = 0; k < textures.size(); ++k) {
    AtlasTile& t = a.tiles[k];
    blit(textures[k].rgba, textures[k], t.x - o.gutter, t.y - o.gutter, pw[k], ph[k], o.gutter, width, a.images[t.atlas]);
    if (with_normals)
      blit(textures[k].normals, textures[k], t.x - o.gutter, t.y - o.gutter, pw[k], ph[k], o.gutter, width,
           a.normal_images[t.atlas]);
    const float w = static_cast<float>(a.widths[t.atlas]), h = static_cast<float>(a.heights[t.atlas]);
    t.u0 = t.x / w, t.u1 = (t.x + t.width) / w;
    t.v0 = t.y / h, t.v1 = (t.y + t.height) / h;
  }
}

}  // namespace

Atlas pack_atlas(const std::vector<Texture>& textures, const AtlasOptions& o) {
  Atlas a;
  a.tiles.resize(textures.size());
  // 1. Padded tile sizes and the packing order.
  std::vector<int> pw(textures.size()), ph(textures.size());
  std::size_t area = 0;
  for (std::size_t k = 0; k < textures.size(); ++k) {
    pw[k] = round_up(textures[k].width + 2 * o.gutter, o.block);  // gutter on every side
    ph[k] = round_up(textures[k].height + 2 * o.gutter, o.block);
    if (pw[k] > o.max_side || ph[k] > o.max_side) throw std::logic_error("pack_atlas: a texture is larger than max_side");
    area += static_cast<std::size_t>(pw[k]) * static_cast<std::size_t>(ph[k]);
    a.texels += static_cast<std::size_t>(textures[k].width) * static_cast<std::size_t>(textures[k].height);
  }
  std::vector<std::size_t> order(textures.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return ph[x] > ph[y]; });
  // 2. Atlas width: the power of two near the square root of the area (at most max_side), and at
  //    least the widest tile.
  int width = o.block;
  while (width < o.max_side && static_cast<std::size_t>(width) * static_cast<std::size_t>(width) < area) width *= 2;
  for (std::size_t k : order)
    while (width < pw[k]) width *= 2;
  // 3. Shelves, 4. images and texture coordinates.
  const std::vector<int> heights = place_on_shelves(pw, ph, order, width, o, a.tiles, textures);
  fill_images(textures, pw, ph, width, heights, o, a);
  // 5. The material channels: factors, and images of those that vary.
  a.channels = level_channels(textures);
  fill_channel_images(textures, pw, ph, o, a);
  return a;
}

LevelChannels level_channels(const std::vector<Texture>& textures) {
  LevelChannels out;
  if (textures.empty() || !std::all_of(textures.begin(), textures.end(), [](const Texture& t) { return !t.orm.empty(); }))
    return out;
  // Occlusion: a texture unless it is 1 (to its byte) wherever the surface is.
  const std::array<float, 2> occlusion = channel_range(textures, 0);
  out.occlusion_texture = occlusion[0] <= occlusion[1] && occlusion[0] * 255.0 < 254.0;
  out.orm_texture = out.occlusion_texture || varies_orm(textures, 1) || varies_orm(textures, 2);
  out.roughness = varies_orm(textures, 1) ? 1.0f : constant_value(textures, 1, 1.0f);
  out.metallic = varies_orm(textures, 2) ? 1.0f : constant_value(textures, 2, 0.0f);
  for (std::size_t c = 0; c < 3; ++c) {
    const bool varies = varies_emissive(textures, c);
    out.emissive_texture |= varies;
    out.emissive[c] = varies ? 1.0f : constant_value(textures, 3 + c, 0.0f);
  }
  return out;
}

}  // namespace qf
