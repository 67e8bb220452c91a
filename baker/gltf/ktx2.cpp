// The Basis Universal encoder behind encode_ktx2 (ktx2.h); its headers stay in this file.
#include "gltf/ktx2.h"

#include <encoder/basisu_comp.h>
#include <encoder/basisu_enc.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace qf {
namespace {

basisu::image to_basis_image(const TextureImage& t) {
  basisu::image img(static_cast<std::uint32_t>(t.width), static_cast<std::uint32_t>(t.height));
  std::memcpy(img.get_ptr(), t.rgba.data(), t.rgba.size());
  return img;
}

}  // namespace

BasisCodec parse_basis_codec(const std::string& name) {
  if (name == "etc1s") return BasisCodec::kEtc1s;
  if (name == "uastc") return BasisCodec::kUastc;
  throw std::invalid_argument("'" + name + "' is not a Basis codec (etc1s or uastc)");
}

const char* basis_codec_name(BasisCodec codec) { return codec == BasisCodec::kEtc1s ? "etc1s" : "uastc"; }

std::vector<std::uint8_t> encode_ktx2(const std::vector<TextureImage>& levels, const Ktx2Options& options) {
  static std::once_flag init;
  std::call_once(init, [] { basisu::basisu_encoder_init(); });
  if (levels.empty()) throw std::runtime_error("KTX2 encoding: no image");
  basisu::job_pool pool(static_cast<std::uint32_t>(std::max(1, options.threads)));
  basisu::basis_compressor_params p;
  p.m_pJob_pool = &pool;
  p.m_multithreading = options.threads > 1;
  p.m_status_output = false;
  p.m_print_stats = false;
  p.m_compute_stats = false;
  p.m_read_source_images = false;
  p.m_write_output_basis_files = false;
  p.m_create_ktx2_file = true;
  p.m_ktx2_srgb_transfer_func = options.srgb;
  p.m_perceptual = options.srgb && !options.normal_map;
  // Our own levels (coverage-preserving): the encoder makes none.
  p.m_mip_gen = false;
  p.m_source_images.push_back(to_basis_image(levels[0]));
  basisu::vector<basisu::image> mips;
  for (std::size_t k = 1; k < levels.size(); ++k) mips.push_back(to_basis_image(levels[k]));
  p.m_source_mipmap_images.push_back(mips);
  if (options.normal_map) {
    // What basisu's -normal_map sets: no codebook smoothing across blocks of a normal map.
    p.m_no_selector_rdo = true;
    p.m_no_endpoint_rdo = true;
    p.m_check_for_alpha = false;
  }
  // Effort: UASTC "faster" (1) and ETC1S compression level 1, not the encoders' defaults (2, 2).
  // Measured on bunny00's default set (engine method, 8 views, each level at its own size): the
  // textures' encoding took 4.8 s instead of 11.8 s on 2 cores, PSNR moved by -0.08..+0.15 dB,
  // IoU by at most 0.005; effort 0/0 took 2.5 s but lost up to 0.3 dB more.
  if (options.codec == BasisCodec::kUastc) {
    p.m_uastc = true;
    p.m_pack_uastc_flags = basisu::cPackUASTCLevelFaster;
    p.m_ktx2_uastc_supercompression = basist::KTX2_SS_ZSTANDARD;
    p.m_ktx2_zstd_supercompression_level = 6;
  } else {
    p.m_quality_level = std::clamp(options.etc1s_quality, 1, 255);
    p.m_compression_level = 1;
  }
  basisu::basis_compressor c;
  if (!c.init(p)) throw std::runtime_error("KTX2 encoding: the Basis Universal encoder refused its parameters");
  const basisu::basis_compressor::error_code e = c.process();
  if (e != basisu::basis_compressor::cECSuccess)
    throw std::runtime_error("KTX2 encoding: the Basis Universal encoder failed (error " + std::to_string(static_cast<int>(e)) + ")");
  const basisu::uint8_vec& out = c.get_output_ktx2_file();
  return std::vector<std::uint8_t>(out.begin(), out.end());
}

}  // namespace qf
