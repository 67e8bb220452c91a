// WebP images (EXT_texture_webp, issue 32): a level's atlas images in fewer file bytes than PNG.
// A WebP image carries no mip levels and decodes to RGBA8 like a PNG, so it changes what a user
// downloads, not the GPU memory. libwebp's encoder lives in webp.cpp alone.
#pragma once

#include <cstdint>
#include <vector>

namespace qf {

struct WebpOptions {
  // Lossless (VP8L) or lossy (VP8, YUV 4:2:0) for the colour channels.
  bool lossless = false;
  // Lossy: 0..100, the quantiser (more is larger and closer). Lossless: the effort of the search
  // (0..100, more is smaller and slower; the decoded texels are exact whatever it is).
  int quality = 90;
  // Lossy with alpha: 100 keeps the alpha plane exact (compressed losslessly), which an alpha-tested
  // texture needs: its cutoff turns alpha differences into coverage differences.
  int alpha_quality = 100;
  // Keep the RGB under alpha 0 as given. Off, the encoder flattens it (lossy) or zeroes it
  // (lossless) to save bytes, and bilinear filtering then mixes that into the visible texels.
  bool exact = true;
  // Lossy: the sharp (iterative) RGB to YUV conversion, which keeps colour edges that 4:2:0
  // subsampling would smear; slower.
  bool sharp_yuv = false;
  // Lossless: near-lossless preprocessing, 0..100 (100 = off; less changes texels by more).
  int near_lossless = 100;
  int method = 4;  // 0..6: encoder effort (speed against size)
};

// The settings the bake uses by default, inline: every BakeOptions holds them, also where libwebp
// is not linked (the fuzz targets). By measurement (docs/textures.md, "WebP settings, by measurement": bunny00's vertices, the
// coloured scan b9_training, the generated bush and a 1M-point torus, each level at its own size
// against PNG). Colour + alpha: lossless. Lossy colour (quality 70..95, the alpha plane lossless,
// `exact`) stayed within -0.02..+0.12 dB on the first three, but the torus's colour pattern lost
// 0.28..0.44 dB at every level (90 and 80), past the 0.3 dB bound; lossless costs nothing there and
// is no larger on point sets (their colour is smooth and the exact alpha plane dominates: 1..3%
// smaller than lossy 80..90 on the torus, bunny and b9). Only textured meshes pay: the bush's leaf colour is 75%
// larger than at 80 (--webp-color 80 for those). `exact` keeps the colour bled under alpha 0
// (TextureOptions::extend_colors), which lossless would otherwise zero and the engine's bilinear
// filter and box-filtered mips would then mix in as a dark fringe.
inline WebpOptions default_webp_color() {
  WebpOptions o;
  o.lossless = true;
  o.quality = 75;  // libwebp's default effort
  o.alpha_quality = 100;
  o.exact = true;
  return o;
}

// Normal maps: lossless. They are stored at half the atlas's size (glb.cpp), and lossy WebP halves
// their x and y once more (its chroma is subsampled 2x): on bunny00's default set lossy 90 lost
// 0.04..0.36 dB and 95 0.02..0.32 against PNG, lossless none, for 76 and 62 KB more (421 KB set).
// (At full size lossy 90 had cost only 0.06..0.10 dB.)
inline WebpOptions default_webp_normal() {
  WebpOptions o;
  o.lossless = true;
  o.quality = 75;  // libwebp's default effort
  return o;
}

// The WebP bytes of an image of `channels` (3: RGB, 4: RGBA) 8-bit channels, `w` x `h` texels, rows
// top to bottom. An RGB image is written without alpha. Same pixels and options, same bytes (one
// thread: libwebp's output does not depend on it, and the levels are encoded one at a time).
// Throws std::invalid_argument for a size WebP cannot hold (over 16383 a side) and
// std::runtime_error when the encoder fails.
std::vector<std::uint8_t> encode_webp(const std::uint8_t* pixels, int w, int h, int channels, const WebpOptions& options);

}  // namespace qf
