// PNG encoding through OpenImageIO into a memory buffer (its IOProxy interface). Built as the
// plug-in libqf_png.so that gltf/png_loader.cpp loads on first use: linking OpenImageIO (and the
// ~250 libraries it pulls in: OpenCV, GDAL, FFmpeg...) costs every process 0.35 s at start-up,
// which commands that write no PNG (info, convert, a batch with nothing to do) should not pay.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::vector<std::uint8_t> encode(const std::uint8_t* pixels, int width, int height, int channels) {
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

}  // namespace

// The plug-in's one entry point (C linkage: looked up by name). Returns false with `error` set
// instead of throwing across the dlopen boundary.
extern "C" __attribute__((visibility("default"))) bool qf_encode_png(const std::uint8_t* pixels, int width, int height,
                                                                      int channels, std::vector<std::uint8_t>* out,
                                                                      std::string* error) {
  try {
    *out = encode(pixels, width, height, channels);
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}
