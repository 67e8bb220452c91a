// Image files and metrics on OpenImageIO (see image_ops.h). The arithmetic of the metrics is done
// with ImageBufAlgo on float images; thresholds are steep clamps (c >= t  <=>  clamp((c - t) * 1e6 + 1, 0, 1)).
#include "tools/image_ops.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "core/file_io.h"
#include "gltf/png.h"

namespace qf::render {
namespace IBA = OIIO::ImageBufAlgo;
namespace {

// The RGB channels of an 8-bit RGBA image as floats in 0..1.
OIIO::ImageBuf rgb_float(const Image& img) {
  OIIO::ImageBuf wrapped(OIIO::ImageSpec(img.width, img.height, 4, OIIO::TypeDesc::UINT8), const_cast<std::uint8_t*>(img.rgba.data()));
  OIIO::ImageBuf rgb = IBA::channels(wrapped, 3, {0, 1, 2});
  OIIO::ImageBuf f;
  f.copy(rgb, OIIO::TypeDesc::FLOAT);
  return f;
}

// 1 where the one-channel image is >= t, else 0.
OIIO::ImageBuf at_least(const OIIO::ImageBuf& c, float t) {
  constexpr float kSteep = 1e6f;
  return IBA::clamp(IBA::mad(c, kSteep, 1.0f - t * kSteep), 0.0f, 1.0f);
}

// Sums over all pixels of every channel (PixelStats' own sum fields are internal to OIIO).
double total(const OIIO::ImageBuf& b) {
  const IBA::PixelStats s = IBA::computePixelStats(b);
  const double pixels = static_cast<double>(b.spec().image_pixels());
  double t = 0;
  for (float v : s.avg) t += static_cast<double>(v) * pixels;
  return t;
}

// Coverage c = 1 - mean over RGB of (W - B) (one channel), and the colour over `bg`:
// B + (W - B) * bg.
void coverage_and_color(const RenderPair& r, const float bg[3], OIIO::ImageBuf& coverage, OIIO::ImageBuf& color) {
  const OIIO::ImageBuf b = rgb_float(r.over_black), w = rgb_float(r.over_white);
  const OIIO::ImageBuf open = IBA::sub(w, b);
  const float third[3] = {1.0f / 3, 1.0f / 3, 1.0f / 3};
  // 1 - x as mad(x, -1, 1): OIIO 2.4's sub(constant, image) computes image - constant.
  coverage = IBA::mad(IBA::channel_sum(open, third), -1.0f, 1.0f);
  color = IBA::mad(open, OIIO::cspan<float>(bg, 3), b);
}

}  // namespace

Image load_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError("render.image", path, "", "cannot read the image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels < 3 || spec.nchannels > 4 || spec.width <= 0 || spec.height <= 0)
    throw InputError("render.image", path, "", "expected an RGB or RGBA image, got " + std::to_string(spec.nchannels) + " channels");
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) * static_cast<std::size_t>(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, raw.data()))
    throw InputError("render.image", path, "", "cannot decode the image: " + in->geterror());
  Image img{spec.width, spec.height, std::vector<std::uint8_t>(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) * 4, 255)};
  for (std::size_t i = 0, n = img.rgba.size() / 4; i < n; ++i)
    for (std::size_t c = 0; c < static_cast<std::size_t>(spec.nchannels); ++c) img.rgba[i * 4 + c] = raw[i * static_cast<std::size_t>(spec.nchannels) + c];
  return img;
}

void save_png(const std::string& path, const Image& image) {
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = image.rgba[i * 4 + c];
  write_bytes_atomically(path, encode_png(rgb.data(), image.width, image.height, 3));
}

Image contact_sheet(const std::vector<Image>& images, int columns, Rgb8 background, const std::vector<std::string>& captions) {
  if (images.empty()) return {};
  const int w = images[0].width, h = images[0].height, n = static_cast<int>(images.size());
  columns = std::max(1, std::min(columns, n));
  const int rows = (n + columns - 1) / columns, caption_h = captions.empty() ? 0 : 28;
  OIIO::ImageBuf sheet(OIIO::ImageSpec(w * columns, (h + caption_h) * rows, 4, OIIO::TypeDesc::UINT8));
  const float bg[4] = {background.r / 255.0f, background.g / 255.0f, background.b / 255.0f, 1};
  IBA::fill(sheet, bg);
  const float luminance = 0.3f * bg[0] + 0.59f * bg[1] + 0.11f * bg[2];
  const float ink[4] = {luminance > 0.5f ? 0.0f : 1.0f, luminance > 0.5f ? 0.0f : 1.0f, luminance > 0.5f ? 0.0f : 1.0f, 1};
  for (int i = 0; i < n; ++i) {
    const int x = (i % columns) * w, y = (i / columns) * (h + caption_h);
    OIIO::ImageBuf tile(OIIO::ImageSpec(w, h, 4, OIIO::TypeDesc::UINT8), const_cast<std::uint8_t*>(images[static_cast<std::size_t>(i)].rgba.data()));
    IBA::paste(sheet, x, y, 0, 0, tile);
    if (i < static_cast<int>(captions.size()))
      IBA::render_text(sheet, x + w / 2, y + h + 20, captions[static_cast<std::size_t>(i)], 16, "DejaVuSans", ink,
                       IBA::TextAlignX::Center);  // no font installed: no caption (not an error)
  }
  Image out;
  out.width = w * columns;
  out.height = (h + caption_h) * rows;
  out.rgba.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 4);
  sheet.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, out.rgba.data());
  return out;
}

ViewMetrics compare_renders(const RenderPair& reference, const RenderPair& impostor, Rgb8 background, std::vector<float>* diff) {
  const float bg[3] = {background.r / 255.0f, background.g / 255.0f, background.b / 255.0f};
  OIIO::ImageBuf cov_r, col_r, cov_i, col_i;
  coverage_and_color(reference, bg, cov_r, col_r);
  coverage_and_color(impostor, bg, cov_i, col_i);
  const OIIO::ImageBuf in_r = at_least(cov_r, 0.5f), in_i = at_least(cov_i, 0.5f), solid_i = at_least(cov_i, 0.9f);
  const OIIO::ImageBuf either = IBA::max(in_r, in_i), both = IBA::mul(in_r, in_i);
  const OIIO::ImageBuf abs_diff = IBA::absdiff(col_r, col_i);
  const OIIO::ImageBuf masked = IBA::mul(abs_diff, IBA::channels(either, 3, {0, 0, 0}));

  ViewMetrics m;
  const double n_either = total(either), n_ref = total(in_r), n_both = total(both);
  const double sum = total(masked), sum2 = total(IBA::mul(masked, masked));
  m.covered = static_cast<std::size_t>(n_ref);
  m.iou = n_either > 0 ? n_both / n_either : 1.0;
  const OIIO::ImageBuf cr = IBA::clamp(cov_r, 0.0f, 1.0f), ci = IBA::clamp(cov_i, 0.0f, 1.0f);
  const double soft_max = total(IBA::max(cr, ci));
  m.soft_iou = soft_max > 0 ? total(IBA::min(cr, ci)) / soft_max : 1.0;
  m.mae = n_either > 0 ? sum / (3 * n_either) : 0.0;
  const double mse = n_either > 0 ? sum2 / (3 * n_either) : 0.0;
  m.psnr = mse > 0 ? std::min(99.0, 10 * std::log10(1.0 / mse)) : 99.0;
  // Mean grey (0..255, the mean of R, G, B) over each image's own covered pixels.
  const double n_imp = total(in_i);
  if (n_imp > 0) m.brightness = 255 * total(IBA::mul(col_i, IBA::channels(in_i, 3, {0, 0, 0}))) / (3 * n_imp);
  if (n_ref > 0) m.reference_brightness = 255 * total(IBA::mul(col_r, IBA::channels(in_r, 3, {0, 0, 0}))) / (3 * n_ref);
  if (n_ref > 0) {
    m.holes = (n_ref - n_both) / n_ref;
    m.see_through = (n_both - total(IBA::mul(in_r, solid_i))) / n_ref;
  }
  if (diff) {
    diff->resize(static_cast<std::size_t>(reference.over_black.width) * static_cast<std::size_t>(reference.over_black.height) * 3);
    abs_diff.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, diff->data());
  }
  return m;
}

void save_exr(const std::string& path, const std::vector<float>& rgb, int width, int height) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto out = OIIO::ImageOutput::create("exr", &proxy);
  if (!out) throw std::runtime_error("EXR encoder unavailable: " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::HALF);
  spec.attribute("compression", "zip");
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) || !out->close())
    throw std::runtime_error("EXR encoding failed: " + out->geterror());
  write_bytes_atomically(path, bytes);
}

Image to_8bit(const std::vector<float>& rgb, int width, int height, float gain) {
  Image out;
  out.width = width;
  out.height = height;
  out.rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 255);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      out.rgba[i * 4 + c] = static_cast<std::uint8_t>(std::clamp(rgb[i * 3 + c] * gain, 0.0f, 1.0f) * 255 + 0.5f);
  return out;
}

// A plain loop: OIIO's resize (a general filter through pixel iterators) took 27% of a mesh bake
// with its recommended chain, most of the chain's time.
Image box_downsample(const Image& image, int factor) {
  if (factor <= 1) return image;
  const std::size_t f = static_cast<std::size_t>(factor), in_w = static_cast<std::size_t>(image.width);
  Image out{image.width / factor, image.height / factor, {}};
  const std::size_t w = static_cast<std::size_t>(out.width), h = static_cast<std::size_t>(out.height);
  std::vector<std::uint32_t> sums(w * 4);
  out.rgba.resize(w * h * 4);
  for (std::size_t y = 0; y < h; ++y) {
    std::fill(sums.begin(), sums.end(), 0u);
    for (std::size_t j = 0; j < f; ++j) {
      const std::uint8_t* row = image.rgba.data() + (y * f + j) * in_w * 4;
      for (std::size_t x = 0; x < w * f; ++x)
        for (std::size_t c = 0; c < 4; ++c) sums[(x / f) * 4 + c] += row[x * 4 + c];
    }
    for (std::size_t i = 0; i < w * 4; ++i) out.rgba[y * w * 4 + i] = static_cast<std::uint8_t>((sums[i] + f * f / 2) / (f * f));
  }
  return out;
}

}  // namespace qf::render
