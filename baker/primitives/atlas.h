// Texture atlas of one level: every primitive's texture packed into one image (several only past
// a size limit), so an engine draws the level with one material and one draw call.
#pragma once

#include <cstdint>
#include <vector>

#include "primitives/texture.h"

namespace qf {

struct AtlasOptions {
  // Each tile gets a cell of whole `block` x `block` blocks holding the texture `gutter` texels in
  // from every side, the rest of the cell repeating the texture's edge texels: bilinear filtering
  // and mipmap levels up to log2(block) then only ever mix a tile with itself.
  int block = 8;
  int gutter = 2;
  int max_side = 4096;  // a power of two; an atlas never exceeds it, more tiles open another atlas
};

struct AtlasTile {
  std::uint32_t atlas = 0;    // which image
  int x = 0, y = 0;           // texel offset of the texture's top-left texel in the image
  int width = 0, height = 0;  // the texture's size
  // The tile in texture coordinates of its atlas (0..1, v down from the top row as glTF has it):
  // the quad's corners map exactly to the tile's outer texel edges.
  float u0 = 0, v0 = 0, u1 = 0, v1 = 0;
};

struct Atlas {
  std::vector<int> widths, heights;                // per image; powers of two
  std::vector<std::vector<std::uint8_t>> images;  // RGBA8, rows top to bottom
  std::vector<std::vector<std::uint8_t>> normal_images;  // the normal maps, same layout (when every texture has one)
  std::vector<AtlasTile> tiles;                    // per input texture, in input order
  std::size_t texels = 0;                          // used by tiles (gutters not counted)
};

// Packs the textures (shelves, tallest first, ties by index: deterministic). A texture bigger than
// max_side is a contract violation (TextureOptions::max_side keeps them smaller).
Atlas pack_atlas(const std::vector<Texture>& textures, const AtlasOptions& options = {});

}  // namespace qf
