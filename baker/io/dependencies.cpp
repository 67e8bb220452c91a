// The files a model reads besides itself (model_io.h, input_dependencies): a glTF's external
// buffers and images, an OBJ's MTL libraries and their map_Kd images, found from the text alone.
#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>
#include <system_error>

#include "core/file_io.h"
#include "io/gltf_json.h"
#include "io/model_io.h"
#include "io/mtl_read.h"
#include "io/reader_util.h"

namespace qf {
namespace {

namespace fs = std::filesystem;

// glTF URIs are percent-encoded (RFC 3986); tinygltf decodes them before opening the file, so
// the same file is found here.
std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    const auto hex = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1; };
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// Adds `name` (relative to the model's folder) once, in the order first met.
void add(std::vector<InputDependency>& out, const fs::path& folder, const fs::path& name) {
  const std::string n = name.lexically_normal().generic_string();
  if (n.empty() || std::any_of(out.begin(), out.end(), [&](const InputDependency& d) { return d.name == n; })) return;
  out.push_back({n, (folder / name).string()});
}

void gltf_dependencies(ByteView bytes, const fs::path& folder, std::vector<InputDependency>& out) {
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
      add(out, folder, fs::path(percent_decoded(uri->get<std::string>())));
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
    add(out, folder, fs::path(mtl));
    std::error_code ec;
    const fs::path mtl_path = folder / mtl;
    if (!fs::is_regular_file(mtl_path, ec)) continue;  // a missing MTL is only a warning to the reader
    const InputFile file(mtl_path.string());
    // Images are relative to the MTL file, which may sit in another folder than the OBJ.
    for (const std::string& image : lines_of(file.bytes(), "map_Kd", true))
      add(out, folder, fs::path(mtl).parent_path() / image);
  }
}

}  // namespace

std::vector<InputDependency> input_dependencies(const std::string& path) {
  std::vector<InputDependency> out;
  const std::string ext = file_extension(path);
  if (ext != "gltf" && ext != "glb" && ext != "obj") return out;
  const InputFile file(path);
  const fs::path folder = fs::path(path).parent_path();
  if (ext == "obj") obj_dependencies(file.bytes(), folder, out);
  else gltf_dependencies(file.bytes(), folder, out);
  return out;
}

}  // namespace qf
