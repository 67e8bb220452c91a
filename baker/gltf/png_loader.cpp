// encode_png through the plug-in libqf_png.so (gltf/png.cpp), loaded once on first use.
#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>

#include "gltf/png.h"

namespace qf {
namespace {

using EncodeFn = bool (*)(const std::uint8_t*, int, int, int, std::vector<std::uint8_t>*, std::string*);

// Where the plug-in may be: $QF_PLUGIN_DIR, beside the executable (the build tree), the install
// layout's lib/quasiflat, then the loader's own search path.
EncodeFn load_encoder() {
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
      if (void* fn = ::dlsym(handle, "qf_encode_png")) return reinterpret_cast<EncodeFn>(fn);
      errors += "; " + path + ": no qf_encode_png";
    } else {
      errors += std::string("; ") + ::dlerror();
    }
  }
  throw std::runtime_error("cannot load the PNG encoder plug-in libqf_png.so (looked beside the executable, in "
                           "../lib/quasiflat and on the library path" + errors + ")");
}

EncodeFn encoder() {
  static std::once_flag once;
  static EncodeFn fn = nullptr;
  static std::string failure;
  std::call_once(once, [] {
    try {
      fn = load_encoder();
    } catch (const std::exception& e) {
      failure = e.what();
    }
  });
  if (!fn) throw std::runtime_error(failure);
  return fn;
}

}  // namespace

void preload_png_encoder() { encoder(); }

std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels) {
  std::vector<std::uint8_t> out;
  std::string error;
  if (!encoder()(pixels, width, height, channels, &out, &error)) throw std::runtime_error(error);
  return out;
}

}  // namespace qf
