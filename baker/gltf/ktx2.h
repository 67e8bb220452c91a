// KTX2 files of Basis Universal textures (KHR_texture_basisu): a level's atlas images with their
// mip levels written in, so an engine transcodes them to its GPU's block format (BC7, ETC2, ASTC:
// 1 byte a texel) instead of decoding a PNG to 4. Basis Universal 1.16.4 lives in this file alone
// (third_party/basis_universal).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"

namespace qf {

enum class BasisCodec {
  kEtc1s,  // ETC1S: small (~1-2 bits a texel), lossy in colour
  kUastc,  // UASTC with zstd supercompression: ~4-8 bits a texel, near BC7 quality
};
BasisCodec parse_basis_codec(const std::string& name);  // "etc1s" | "uastc"; throws std::invalid_argument
const char* basis_codec_name(BasisCodec codec);

struct Ktx2Options {
  BasisCodec codec = BasisCodec::kEtc1s;
  bool srgb = true;         // the KTX2 transfer function: sRGB (colour, emission) or linear (data)
  bool normal_map = false;  // the encoder's normal-map mode: linear metric, no rate-distortion smoothing
  int etc1s_quality = 128;  // 1..255 (basisu -q): endpoint and selector codebook sizes
  int threads = 1;          // the encoder's job pool (its output does not depend on it)
};

// The KTX2 bytes of `levels` (element 0 the base, each next one half the size, RGBA8 rows top to
// bottom, as primitives/mip_levels.h makes them). Same levels and options, same bytes. Throws
// std::runtime_error when the encoder fails.
std::vector<std::uint8_t> encode_ktx2(const std::vector<TextureImage>& levels, const Ktx2Options& options);

}  // namespace qf
