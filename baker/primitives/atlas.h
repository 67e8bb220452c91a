// Texture atlas of one level: every primitive's texture packed into one image (several only past
// a size limit), so an engine draws the level with one material and one draw call.
#pragma once

#include <array>
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

// A level's material channels (issue 31): each one a factor where it is the same over the texels
// the surface covers in every tile (within 1/255 once encoded: linear bytes for occlusion,
// roughness and metallic, sRGB bytes for emission), else a texture in the atlas layout. Texture
// channels of a constant channel hold 255, so texel x factor is the factor itself; occlusion has
// no factor (glTF): it is a texture unless it is 1 everywhere. Textures without channels (point
// sets, meshes without materials) give the defaults: a rough dielectric without emission.
struct LevelChannels {
  float roughness = 1, metallic = 0;
  std::array<float, 3> emissive{0, 0, 0};  // linear
  bool orm_texture = false;       // occlusion, roughness or metallic varies: Atlas::orm_images
  bool occlusion_texture = false;  // ... and the ORM images' R is the level's occlusion
  bool emissive_texture = false;  // an emissive channel varies: Atlas::emissive_images
};
LevelChannels level_channels(const std::vector<Texture>& textures);

struct Atlas {
  std::vector<int> widths, heights;                // per image; powers of two
  std::vector<std::vector<std::uint8_t>> images;  // RGBA8, rows top to bottom
  std::vector<std::vector<std::uint8_t>> normal_images;  // the normal maps, same layout (when every texture has one)
  LevelChannels channels;                                  // the level's material channels
  std::vector<std::vector<std::uint8_t>> orm_images;       // same layout, when channels.orm_texture
  std::vector<std::vector<std::uint8_t>> emissive_images;  // same layout, when channels.emissive_texture
  std::vector<AtlasTile> tiles;                    // per input texture, in input order
  std::size_t texels = 0;                          // used by tiles (gutters not counted)
};

// Packs the textures (shelves, tallest first, ties by index: deterministic). A texture bigger than
// max_side is a contract violation (TextureOptions::max_side keeps them smaller).
Atlas pack_atlas(const std::vector<Texture>& textures, const AtlasOptions& options = {});

}  // namespace qf
