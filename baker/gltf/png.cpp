// PNG encoding and image decoding through OpenImageIO in memory (its IOProxy interface). Built as the
// plug-in libqf_png.so that gltf/png_loader.cpp loads on first use: linking OpenImageIO (and the
// ~250 libraries it pulls in: OpenCV, GDAL, FFmpeg...) costs every process 0.35 s at start-up,
// which commands that write no PNG (info, convert, a batch with nothing to do) should not pay.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
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

// The format to decode as: PNG and JPEG by their signatures (a texture's file name may not say),
// else whatever the name's extension says (OIIO's other readers: TGA, BMP, TIFF, WebP...).
std::string format_name(const std::uint8_t* bytes, std::size_t size, const std::string& name) {
  if (size >= 8 && bytes[0] == 0x89 && bytes[1] == 'P' && bytes[2] == 'N' && bytes[3] == 'G') return "image.png";
  if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "image.jpg";
  return name;
}

bool is_png_name(const std::string& format) {
  if (format.size() < 4) return false;
  std::string ext = format.substr(format.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png";
}

// OIIO 2.4 reports a PNG stream that ends early (its read callback got fewer bytes than libpng
// asked for) by a longjmp out of libpng past a std::string temporary, which leaks (found by
// fuzzing the glTF reader with truncated embedded textures). So the chunks are walked first:
// the signature, then length, type, data and CRC of each chunk within the bytes, up to IEND.
void check_png_chunks(const std::uint8_t* bytes, std::size_t size) {
  static const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size < 8 || !std::equal(kSignature, kSignature + 8, bytes)) throw std::runtime_error("is not a PNG file (no PNG signature)");
  for (std::size_t at = 8;;) {
    if (size - at < 12) throw std::runtime_error("is a truncated PNG file (it ends within a chunk, before IEND)");
    const std::size_t length = std::size_t{bytes[at]} << 24 | std::size_t{bytes[at + 1]} << 16 | std::size_t{bytes[at + 2]} << 8 | bytes[at + 3];
    if (length > size - at - 12) throw std::runtime_error("is a truncated PNG file (a chunk of " + std::to_string(length) + " bytes ends past its end)");
    const bool end = bytes[at + 4] == 'I' && bytes[at + 5] == 'E' && bytes[at + 6] == 'N' && bytes[at + 7] == 'D';
    at += 12 + length;
    if (end) return;
  }
}

void decode(const std::uint8_t* bytes, std::size_t size, const std::string& name, int* width, int* height,
            std::vector<std::uint8_t>* rgba) {
  if (is_png_name(format_name(bytes, size, name))) check_png_chunks(bytes, size);
  OIIO::Filesystem::IOMemReader proxy(bytes, size);
  // Straight alpha, as the files store it (OIIO would premultiply PNG colour by alpha otherwise).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::Filesystem::IOProxy* proxy_ptr = &proxy;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_ptr);
  auto in = OIIO::ImageInput::open(format_name(bytes, size, name), &config, &proxy);
  if (!in) throw std::runtime_error("does not decode as an image (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  const int channels = spec.nchannels;
  // A cap against crafted headers: 16384^2 texels is past any texture an engine loads.
  if (spec.width <= 0 || spec.height <= 0 || spec.width > 16384 || spec.height > 16384 || channels < 1 || channels > 64)
    throw std::runtime_error("has an unusable size (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                             ", " + std::to_string(channels) + " channels)");
  const std::size_t n = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
  std::vector<std::uint8_t> raw(n * static_cast<std::size_t>(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data()))
    throw std::runtime_error("does not decode as an image (" + in->geterror() + ")");
  // Grey, grey + alpha, RGB or RGBA (and more channels: the first four) -> RGBA.
  rgba->assign(n * 4, 255);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* t = &raw[i * static_cast<std::size_t>(channels)];
    std::uint8_t* o = &(*rgba)[i * 4];
    if (channels <= 2) {
      o[0] = o[1] = o[2] = t[0];
      if (channels == 2) o[3] = t[1];
    } else {
      for (int c = 0; c < std::min(channels, 4); ++c) o[c] = t[c];
    }
  }
  *width = spec.width;
  *height = spec.height;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) bool qf_decode_image(const std::uint8_t* bytes, std::size_t size,
                                                                        const std::string* name, int* width, int* height,
                                                                        std::vector<std::uint8_t>* rgba,
                                                                        std::string* error) {
  try {
    decode(bytes, size, *name, width, height, rgba);
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}

// The plug-in's encoding entry point (C linkage: looked up by name). Returns false with `error` set
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
