// The files a model reads besides itself (model_io.h, input_dependencies): a glTF's external
// buffers and images, an OBJ's MTL libraries and their map_Kd images, found from the text alone.
#include <algorithm>
#include <optional>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>
#include <system_error>

#include "core/error.h"
#include "core/file_io.h"
#include "core/input_limits.h"
#include "io/asset_files.h"
#include "io/gltf_json.h"
#include "io/model_io.h"
#include "io/mtl_read.h"
#include "io/reader_util.h"

namespace qf {
namespace {

namespace fs = std::filesystem;

// Adds `name` (as the model names it, relative to `base`) once, in the order first met, by the
// reader's rule (io/asset_files.h): a name leading outside the asset's folder is left out (the
// reader refuses the asset, and a content key must not read, hash or reveal files outside it);
// it is opened by the path found inside, symlinks resolved.
void add(std::vector<InputDependency>& out, const fs::path& root, const fs::path& base, const fs::path& name) {
  const std::string n = name.lexically_normal().generic_string();
  if (n.empty() || std::any_of(out.begin(), out.end(), [&](const InputDependency& d) { return d.name == n; })) return;
  const std::optional<fs::path> inside = io::resolve_inside(root, base, name.generic_string());
  if (inside) out.push_back({n, inside->string()});
}

void gltf_dependencies(ByteView bytes, const fs::path& folder, std::vector<InputDependency>& out) {
  try {
    check_gltf_json_depth(bytes.data(), bytes.size(), "", "gltf");
  } catch (const InputError&) {
    return;  // the reader refuses it
  }
  const nlohmann::json j = io::gltf_json(bytes);  // the JSON exactly as the reader sees it
  if (!j.is_object()) return;  // the reader will say what is wrong
  for (const char* array : {"buffers", "images"}) {
    const auto a = j.find(array);
    if (a == j.end() || !a->is_array()) continue;
    for (const nlohmann::json& item : *a) {
      if (!item.is_object()) continue;
      const auto uri = item.find("uri");
      // data: URIs are inside the file already (so hashed with it).
      if (uri == item.end() || !uri->is_string() || uri->get<std::string>().rfind("data:", 0) == 0) continue;
      add(out, folder, folder, fs::path(io::percent_decoded(uri->get<std::string>())));
    }
  }
}

// The words after `key` on every line of `bytes` that starts with it, joined as the OBJ and MTL
// readers join them ('\' taken as '/', as they do).
std::vector<std::string> lines_of(ByteView bytes, std::string_view key, bool last_word_only) {
  std::vector<std::string> found;
  io::Tokenizer tok(reinterpret_cast<const char*>(bytes.data()), reinterpret_cast<const char*>(bytes.data() + bytes.size()));
  while (!tok.at_end()) {
    const std::string_view k = tok.next_on_line();
    if (k == key) {
      std::vector<std::string_view> words;
      for (std::string_view t = tok.next_on_line(); !t.empty(); t = tok.next_on_line()) words.push_back(t);
      // map_Kd's options (-s, -o, -bm ...) come first; the image is the last word (mtl_read.cpp).
      std::string v = words.empty() ? "" : last_word_only ? std::string(words.back()) : io::join_words(words);
      std::replace(v.begin(), v.end(), '\\', '/');
      if (!v.empty()) found.push_back(v);
    }
    tok.skip_line();
  }
  return found;
}

void obj_dependencies(ByteView bytes, const fs::path& folder, std::vector<InputDependency>& out) {
  for (const std::string& mtl : lines_of(bytes, "mtllib", false)) {
    add(out, folder, folder, fs::path(mtl));
    const std::optional<fs::path> mtl_path = io::resolve_inside(folder, folder, mtl);
    std::error_code ec;
    if (!mtl_path || !fs::is_regular_file(*mtl_path, ec)) continue;  // a missing MTL is only a warning to the reader
    const InputFile file(mtl_path->string());
    // Images are relative to the MTL file, which may sit in another folder than the OBJ.
    for (const std::string& image : lines_of(file.bytes(), "map_Kd", true))
      add(out, folder, folder, fs::path(mtl).parent_path() / image);
  }
}

}  // namespace

std::vector<InputDependency> input_dependencies(const std::string& path) {
  std::vector<InputDependency> out;
  const std::string ext = file_extension(path);
  if (ext != "gltf" && ext != "glb" && ext != "obj") return out;
  const InputFile file(path);
  const fs::path folder = io::asset_root(path, "");  // canonical: the root references stay in
  if (ext == "obj") obj_dependencies(file.bytes(), folder, out);
  else gltf_dependencies(file.bytes(), folder, out);
  return out;
}

}  // namespace qf
