// Batch manifests (schemas/batch.schema.json): reading and checking one, and its shards. Apart from
// the scheduler (batch.cpp) so that the parser links alone (tests/fuzz).
#include <cctype>
#include <filesystem>
#include <set>

#include "core/error.h"
#include "core/file_io.h"
#include "core/hash.h"
#include "pipeline/batch.h"

namespace qf {
namespace {

using Json = nlohmann::json;

// --- the manifest --------------------------------------------------------------------------------

[[noreturn]] void manifest_error(const std::string& path, const std::string& where, const std::string& what) {
  throw InputError("batch.manifest", path, where, what);
}

bool valid_name(const std::string& n) {
  if (n.empty() || n.size() > 200 || n[0] == '.' || n[0] == '-') return false;
  for (char c : n)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') return false;
  return true;
}

// A setting's value: a string, number, boolean, or a list of numbers/strings (joined by commas).
void check_setting(const std::string& path, const std::string& where, const Json& v) {
  if (v.is_string() || v.is_number() || v.is_boolean()) return;
  if (v.is_array() && !v.empty()) {
    for (const Json& x : v)
      if (!x.is_number() && !x.is_string()) manifest_error(path, where, "a list setting holds numbers or strings only");
    return;
  }
  manifest_error(path, where, "expected a string, number, boolean or non-empty list");
}

void check_settings(const std::string& path, const std::string& where, const Json& s) {
  if (!s.is_object()) manifest_error(path, where, "expected an object of bake options (name: value)");
  for (const auto& [k, v] : s.items()) check_setting(path, where + "." + k, v);
}


Json parse_manifest_json(ByteView bytes, const std::string& path) {
  Json j;
  try {
    j = Json::parse(bytes.data(), bytes.data() + bytes.size());
  } catch (const Json::parse_error& e) {
    throw InputError("batch.json", path, at_byte(e.byte), std::string("not valid JSON: ") + e.what());
  } catch (const Json::exception& e) {
    // Valid JSON that nlohmann cannot hold, e.g. a number beyond double (1e400): out_of_range.406.
    throw InputError("batch.json", path, "", std::string("unreadable JSON: ") + e.what());
  }
  if (!j.is_object()) manifest_error(path, "", "expected a JSON object with an \"assets\" list");
  for (const auto& [k, v] : j.items()) {
    (void)v;
    if (k != "$schema" && k != "description" && k != "output" && k != "defaults" && k != "assets")
      manifest_error(path, k, "unknown key (expected $schema, description, output, defaults, assets)");
  }
  return j;
}

// Entry i of "assets": a path, or {input, name, settings}; its settings overlay the defaults.
BatchAsset read_asset_entry(const Json& e, std::size_t i, const Json& defaults, const std::string& path) {
  const std::string where = "assets[" + std::to_string(i) + "]";
  BatchAsset a;
  a.index = i;
  a.settings = defaults;
  if (e.is_string()) {
    a.input = e.get<std::string>();
  } else if (e.is_object()) {
    for (const auto& [k, v] : e.items()) {
      (void)v;
      if (k != "input" && k != "name" && k != "settings") manifest_error(path, where + "." + k, "unknown key (expected input, name, settings)");
    }
    if (!e.contains("input") || !e["input"].is_string()) manifest_error(path, where + ".input", "expected the input file's path");
    a.input = e["input"].get<std::string>();
    if (e.contains("name")) {
      if (!e["name"].is_string()) manifest_error(path, where + ".name", "expected a string");
      a.name = e["name"].get<std::string>();
    }
    if (e.contains("settings")) {
      check_settings(path, where + ".settings", e["settings"]);
      for (const auto& [k, v] : e["settings"].items()) {
        // --levels and --primitives choose the levels two ways: an asset's choice replaces the defaults'.
        if (k == "levels" && !e["settings"].contains("primitives")) a.settings.erase("primitives");
        if (k == "primitives" && !e["settings"].contains("levels")) a.settings.erase("levels");
        a.settings[k] = v;
      }
    }
  } else {
    manifest_error(path, where, "expected an input path or an object {input, name, settings}");
  }
  if (a.input.empty()) manifest_error(path, where + ".input", "expected the input file's path");
  if (a.name.empty()) a.name = std::filesystem::path(a.input).stem().string();
  if (!valid_name(a.name))
    manifest_error(path, where + ".name", "'" + a.name + "' cannot name a folder (letters, digits, '_', '-', '.'; not starting with '.' or '-')");
  return a;
}

}  // namespace

BatchManifest read_batch_manifest(const std::string& path) {
  const InputFile file(path);
  return parse_batch_manifest(file.bytes(), path);
}

BatchManifest parse_batch_manifest(ByteView bytes, const std::string& path) {
  BatchManifest m;
  m.path = path;
  m.sha256 = Sha256().update(bytes).hex();
  const Json j = parse_manifest_json(bytes, path);
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  auto resolve = [&](const std::string& p) {
    const std::filesystem::path q(p);
    return (q.is_absolute() ? q : dir / q).lexically_normal().string();
  };
  if (j.contains("output")) {
    if (!j["output"].is_string() || j["output"].get<std::string>().empty()) manifest_error(path, "output", "expected a folder name");
    m.output = resolve(j["output"].get<std::string>());
  }
  Json defaults = Json::object();
  if (j.contains("defaults")) {
    check_settings(path, "defaults", j["defaults"]);
    defaults = j["defaults"];
  }
  if (!j.contains("assets") || !j["assets"].is_array() || j["assets"].empty())
    manifest_error(path, "assets", "expected a non-empty list of assets");
  std::set<std::string> names;
  for (std::size_t i = 0; i < j["assets"].size(); ++i) {
    BatchAsset a = read_asset_entry(j["assets"][i], i, defaults, path);
    if (!names.insert(a.name).second)
      manifest_error(path, "assets[" + std::to_string(i) + "].name", "'" + a.name + "' names two assets; give one a \"name\"");
    a.path = resolve(a.input);
    m.assets.push_back(std::move(a));
  }
  return m;
}

std::vector<std::size_t> shard_assets(std::size_t assets, int index, int count) {
  std::vector<std::size_t> out;
  for (std::size_t i = static_cast<std::size_t>(index - 1); i < assets; i += static_cast<std::size_t>(count)) out.push_back(i);
  return out;
}

}  // namespace qf
