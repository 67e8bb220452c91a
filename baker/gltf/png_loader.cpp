// encode_png and decode_image through the plug-in libqf_png.so (gltf/png.cpp), loaded once on first use.
#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>

#include "gltf/png.h"

namespace qf {
namespace {

using EncodeFn = bool (*)(const std::uint8_t*, int, int, int, std::vector<std::uint8_t>*, std::string*);
using DecodeFn = bool (*)(const std::uint8_t*, std::size_t, const std::string*, int*, int*, std::vector<std::uint8_t>*,
                          std::string*);

struct Plugin {
  EncodeFn encode = nullptr;
  DecodeFn decode = nullptr;
};

// Where the plug-in may be: $QF_PLUGIN_DIR, beside the executable (the build tree), the install
// layout's lib/quasiflat, then the loader's own search path.
Plugin load_plugin() {
  std::vector<std::string> candidates;
  if (const char* dir = std::getenv("QF_PLUGIN_DIR"); dir && *dir) candidates.push_back(std::string(dir) + "/libqf_png.so");
  std::error_code ec;
  const std::filesystem::path exe_dir = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path();
  if (!ec) {
    candidates.push_back((exe_dir / "libqf_png.so").string());
    candidates.push_back((exe_dir / "../lib/quasiflat/libqf_png.so").string());
  }
  candidates.push_back("libqf_png.so");
  std::string errors;
  for (const std::string& path : candidates) {
    if (path.find('/') != std::string::npos && !std::filesystem::exists(path, ec)) continue;
    if (void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
      void* encode = ::dlsym(handle, "qf_encode_png");
      void* decode = ::dlsym(handle, "qf_decode_image");
      if (encode && decode) return Plugin{reinterpret_cast<EncodeFn>(encode), reinterpret_cast<DecodeFn>(decode)};
      errors += "; " + path + ": no qf_encode_png / qf_decode_image";
    } else {
      errors += std::string("; ") + ::dlerror();
    }
  }
  throw std::runtime_error("cannot load the image plug-in libqf_png.so (looked beside the executable, in "
                           "../lib/quasiflat and on the library path" + errors + ")");
}

const Plugin& plugin() {
  static std::once_flag once;
  static Plugin fns;
  static std::string failure;
  std::call_once(once, [] {
    try {
      fns = load_plugin();
    } catch (const std::exception& e) {
      failure = e.what();
    }
  });
  if (!fns.encode) throw std::runtime_error(failure);
  return fns;
}

}  // namespace

void preload_png_encoder() { plugin(); }

std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels) {
  std::vector<std::uint8_t> out;
  std::string error;
  if (!plugin().encode(pixels, width, height, channels, &out, &error)) throw std::runtime_error(error);
  return out;
}

TextureImage decode_image(const std::uint8_t* bytes, std::size_t size, const std::string& name) {
  TextureImage image;
  std::string error;
  if (!plugin().decode(bytes, size, &name, &image.width, &image.height, &image.rgba, &error)) throw std::runtime_error(error);
  return image;
}

}  // namespace qf
