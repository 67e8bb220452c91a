// MTL material libraries (mtl_read.h).
#include "io/mtl_read.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/error.h"
#include "gltf/png.h"
#include "io/reader_util.h"

namespace qf::io {

std::string join_words(const std::vector<std::string_view>& words) {
  std::string out;
  for (std::string_view w : words) out += (out.empty() ? "" : " ") + std::string(w);
  return out;
}

namespace {

std::filesystem::path beside(const std::string& file, std::string relative) {
  std::replace(relative.begin(), relative.end(), '\\', '/');
  return std::filesystem::path(file).parent_path() / relative;
}

TextureImage load_texture(const std::filesystem::path& image, const std::string& mtl, std::size_t line) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(image, ec))
    throw InputError("mtl.image", mtl, "line " + std::to_string(line), "map_Kd names " + image.string() + ", which does not exist");
  const InputFile file(image.string());
  try {
    return decode_image(file.bytes().data(), file.bytes().size(), image.string());
  } catch (const std::runtime_error& e) {
    throw InputError("mtl.image", mtl, "line " + std::to_string(line), "map_Kd " + image.string() + ": " + e.what());
  }
}

}  // namespace

void read_mtl(const std::string& obj_path, const std::string& mtl_path, TriangleMesh& mesh, MaterialLibrary& library,
              ReadReport* report) {
  const std::filesystem::path path = beside(obj_path, mtl_path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    if (report) report->warnings.push_back("mtllib " + mtl_path + " not found: its materials are left uncoloured");
    return;
  }
  const InputFile file(path.string());
  const ByteView bytes = file.bytes();
  Tokenizer tok(reinterpret_cast<const char*>(bytes.data()), reinterpret_cast<const char*>(bytes.data() + bytes.size()));
  SurfaceMaterial* current = nullptr;
  while (!tok.at_end()) {
    const std::size_t line = tok.line();
    const std::string_view key = tok.next_on_line();
    std::vector<std::string_view> words;
    for (std::string_view t = tok.next_on_line(); !t.empty(); t = tok.next_on_line()) words.push_back(t);
    if (key == "newmtl") {
      const std::string name = join_words(words);
      const auto found = library.by_name.find(name);
      if (found == library.by_name.end()) {
        library.by_name[name] = static_cast<std::uint32_t>(mesh.materials.size());
        mesh.materials.push_back({});
        mesh.materials.back().name = name;
      }
      current = &mesh.materials[library.by_name[name]];
    } else if (current && (key == "Kd" || key == "Ke") && words.size() >= 3) {
      // Kd: the diffuse colour (glTF's base colour); Ke: the emitted colour (glTF's emissive factor).
      float* out = key == "Kd" ? current->base_color.data() : current->emissive.data();
      for (int c = 0; c < 3; ++c) {
        double v = 0;
        if (!parse_double(words[static_cast<std::size_t>(c)], v) || !std::isfinite(v))
          throw InputError("mtl.bad_number", path.string(), "line " + std::to_string(line),
                           "expected '" + std::string(key) + " r g b' with numbers");
        // MTL colours are sRGB, like the textures they multiply.
        v = std::clamp(v, 0.0, 1.0);
        out[c] = static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
      }
    } else if (current && key == "map_Kd" && !words.empty()) {
      // Options (-s, -o, -bm ...) come first; the image is the last word.
      current->texture = static_cast<int>(mesh.textures.size());
      mesh.textures.push_back(load_texture(beside(path.string(), std::string(words.back())), path.string(), line));
    }
    tok.skip_line();
  }
}

}  // namespace qf::io
