// Image files on OpenImageIO (see image_ops.h).
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

}  // namespace qf::render
