// PNG encoding through OpenImageIO into a memory buffer (its IOProxy interface).
#include "gltf/png.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <stdexcept>
#include <string>

namespace qf {

std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto out = OIIO::ImageOutput::create("png", &proxy);
  if (!out) throw std::runtime_error("PNG encoder unavailable: " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  // Fixed settings: no timestamps or software tags, so identical pixels give identical files.
  spec.attribute("png:compressionLevel", 6);
  // Our pixels have straight alpha, as PNG and glTF store it. Without this OIIO takes them as
  // premultiplied and divides colour by alpha on the way out (found by rendering the baked
  // levels: low-alpha texels came out white).
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out->open("image.png", spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels) || !out->close())
    throw std::runtime_error("PNG encoding failed: " + out->geterror());
  return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
}

}  // namespace qf
