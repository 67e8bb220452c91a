// MTL material libraries (mtl_read.h).
#include "io/mtl_read.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/error.h"
#include "core/input_limits.h"
#include "io/asset_files.h"
#include "gltf/png.h"
#include "io/reader_util.h"

namespace qf::io {

std::string join_words(const std::vector<std::string_view>& words) {
  std::string out;
  for (std::string_view w : words) out += (out.empty() ? "" : " ") + std::string(w);
  return out;
}

namespace {

std::string slashes(std::string relative) {
  std::replace(relative.begin(), relative.end(), '\\', '/');
  return relative;
}

// The image of a map_Kd line (`written` as the MTL writes it, relative to the MTL's folder),
// confined to the asset's folder; InputError "mtl.image" where it is missing.
std::filesystem::path texture_path(const std::filesystem::path& mtl_folder, const std::string& written, const std::string& mtl,
                                   std::size_t line, const MaterialLibrary& library) {
  const std::string where = "line " + std::to_string(line);
  const std::filesystem::path image = confined_file(library.root, mtl_folder, slashes(written), written, mtl, "mtl", where);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(image, ec))
    throw InputError("mtl.image", mtl, where, "map_Kd names " + written + ", which does not exist");
  return image;
}

TextureImage load_texture(const std::filesystem::path& mtl_folder, const std::string& written, const std::string& mtl, std::size_t line,
                          const MaterialLibrary& library) {
  const std::filesystem::path image = texture_path(mtl_folder, written, mtl, line, library);
  const InputFile file(image.string());
  try {
    return decode_image(file.bytes().data(), file.bytes().size(), image.string());
  } catch (const std::runtime_error& e) {
    throw InputError("mtl.image", mtl, "line " + std::to_string(line), "map_Kd " + written + ": " + e.what());
  }
}

// Before any image of the MTL `bytes` is decoded: every map_Kd image's decoded size from its
// header, added to the images of the MTL files before it, checked against the memory limit (one
// 1 MB PNG named 8 times decodes to 8 GB).
void check_texture_memory(ByteView bytes, const std::filesystem::path& path, MaterialLibrary& library) {
  Tokenizer tok(reinterpret_cast<const char*>(bytes.data()), reinterpret_cast<const char*>(bytes.data() + bytes.size()));
  std::size_t images = 0;
  while (!tok.at_end()) {
    const std::size_t line = tok.line();
    const std::string_view key = tok.next_on_line();
    std::string_view last;
    for (std::string_view t = tok.next_on_line(); !t.empty(); t = tok.next_on_line()) last = t;
    tok.skip_line();
    if (key != "map_Kd" || last.empty()) continue;
    const std::string written(last);
    const std::filesystem::path image = confined_file(library.root, path.parent_path(), slashes(written), written, path.string(), "mtl",
                                                      "line " + std::to_string(line));
    std::error_code ec;
    if (!std::filesystem::is_regular_file(image, ec)) continue;  // refused where a material uses it
    const InputFile file(image.string());
    if (const std::optional<ImageHeader> h = image_header(file.bytes().data(), file.bytes().size()))
      library.image_bytes += decoded_image_bytes(*h), ++images;
  }
  check_memory_need(library.image_bytes, library.memory_limit, path.string(), "mtl.memory", "",
                    "decoding its " + std::to_string(images) + " map_Kd images (with those of the MTL files before it)");
}

}  // namespace

void read_mtl(const std::string& obj_path, const std::string& mtl_path, std::size_t obj_line, TriangleMesh& mesh,
              MaterialLibrary& library, ReadReport* report) {
  const std::filesystem::path path = confined_file(library.root, std::filesystem::path(obj_path).parent_path(), slashes(mtl_path),
                                                   mtl_path, obj_path, "obj", "line " + std::to_string(obj_line));
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    if (report) report->warnings.push_back("mtllib " + mtl_path + " not found: its materials are left uncoloured");
    return;
  }
  const InputFile file(path.string());
  const ByteView bytes = file.bytes();
  check_texture_memory(bytes, path, library);
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
      mesh.textures.push_back(load_texture(path.parent_path(), std::string(words.back()), path.string(), line, library));
    }
    tok.skip_line();
  }
}

}  // namespace qf::io
