// The colour a standard engine shows at a point of a mesh's surface (glTF 2.0, 3.9.2): the
// material's baseColorFactor x its base colour texture (bilinear, filtered in linear light) x the
// interpolated vertex colour. Both sampling backends colour their points with it (sample.h).
#pragma once

#include <cstddef>

#include "core/types.h"

namespace qf {

struct SurfaceColor {
  Rgb8 color;          // sRGB
  bool surface = true;  // false where a MASK material's alpha is under its cutoff: a cut-out
};

// At barycentric weights w of triangle t. Meshes without materials and vertex colours give white.
SurfaceColor surface_color(const TriangleMesh& mesh, std::size_t t, const double w[3]);

// The other channels of glTF's metallic-roughness model an engine shows at a point (glTF 2.0
// 3.9.2-3.9.5), linear: occlusion (1 + strength x (texel R - 1)), roughness and metallic (factor x
// texel G, B), and the emitted colour (factor x the sRGB texel, decoded). Texture coordinates as
// for the base colour; a mesh without materials gets the defaults.
struct SurfaceChannels {
  float occlusion = 1, roughness = 1, metallic = 0;
  std::array<float, 3> emissive{0, 0, 0};
};
SurfaceChannels surface_channels(const TriangleMesh& mesh, std::size_t t, const double w[3]);

// The vertex colours of triangle t at barycentric weights w, interpolated in sRGB bytes as stored:
// the colour of a mesh without materials (PLY, OFF), as its sampled points and its quads take it.
Rgb8 interpolated_vertex_color(const TriangleMesh& mesh, std::size_t t, const double w[3]);

// The texel colour of `image` at texture coordinate uv with the given wraps, bilinear between the
// four nearest texel centres in linear light: linear RGB and alpha, each 0..1.
std::array<float, 4> sample_texture(const TextureImage& image, Vec2f uv, TextureWrap wrap_s, TextureWrap wrap_t);

}  // namespace qf
