// Spatial tiles of one scan for a farm, and the join of their baked levels.
#include "pipeline/tiles.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/file_io.h"
#include "gltf/glb.h"

namespace qf {
namespace {

// 1. The k-d split of `idx` into `count` tiles, appended to `out`.
void split(std::vector<std::uint32_t> idx, std::size_t count, const std::vector<Vec3f>& p,
           std::vector<std::vector<std::uint32_t>>& out) {
  if (count <= 1 || idx.size() < 2) {
    std::sort(idx.begin(), idx.end());
    out.push_back(std::move(idx));
    for (std::size_t i = 1; i < count; ++i) out.emplace_back();
    return;
  }
  Bounds b;
  for (std::uint32_t i : idx) b.add(p[i]);
  const Vec3f e = b.size();
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
  // By coordinate, ties by index: the same cut on every machine and standard library.
  std::sort(idx.begin(), idx.end(), [&](std::uint32_t a, std::uint32_t c) {
    return p[a][axis] != p[c][axis] ? p[a][axis] < p[c][axis] : a < c;
  });
  const std::size_t lower_tiles = count / 2;
  const std::size_t cut = idx.size() * lower_tiles / count;
  std::vector<std::uint32_t> upper(idx.begin() + static_cast<std::ptrdiff_t>(cut), idx.end());
  idx.resize(cut);
  split(std::move(idx), lower_tiles, p, out);
  split(std::move(upper), count - lower_tiles, p, out);
}

std::string stem_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

nlohmann::json read_json(const std::string& path, const char* code, const std::string& what) {
  try {
    const InputFile f(path);
    const ByteView b = f.bytes();
    return nlohmann::json::parse(b.data(), b.data() + b.size());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(code, path, "", what + " does not parse: " + e.what());
  } catch (const InputError& e) {
    throw InputError(code, path, "", what + ": " + e.what());
  }
}

std::vector<std::uint8_t> read_bytes(const std::string& path, const std::string& what) {
  try {
    const InputFile f(path);
    const ByteView b = f.bytes();
    return std::vector<std::uint8_t>(b.data(), b.data() + b.size());
  } catch (const InputError& e) {
    throw InputError("join.tile", path, "", what + ": " + e.what());
  }
}

}  // namespace

std::vector<std::vector<std::uint32_t>> spatial_tiles(const std::vector<Vec3f>& positions, std::size_t count) {
  std::vector<std::uint32_t> all(positions.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::uint32_t>(i);
  std::vector<std::vector<std::uint32_t>> out;
  split(std::move(all), count, positions, out);
  return out;
}

TilePlan plan_tiles(const PointSet& points, const std::string& input_name, std::size_t count,
                    const std::vector<std::size_t>& primitives) {
  // A tile needs enough points for its own decomposition (neighbourhoods of up to 50).
  if (count == 0 || count > points.size() / 64)
    throw UsageError("--tiles " + std::to_string(count) + ": between 1 and the points / 64 (" + std::to_string(points.size() / 64) + ")");
  const std::string stem = stem_of(input_name);
  TilePlan t;
  nlohmann::json tiles = nlohmann::json::array(), assets = nlohmann::json::array();
  const std::vector<std::vector<std::uint32_t>> parts = spatial_tiles(points.positions, count);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string name = stem + "_t" + std::to_string(i);
    const std::string file = name + ".ply";
    t.tiles.push_back(permuted(points, parts[i]));
    t.tile_names.push_back(file);
    tiles.push_back({{"name", name},
                     {"file", file},
                     {"points", parts[i].size()},
                     {"bounding_box_diagonal", canonical_double(t.tiles.back().bounds().diagonal())}});
    assets.push_back({{"name", name}, {"input", file}});
  }
  nlohmann::json per_tile = nlohmann::json::array();
  for (std::size_t n : primitives) per_tile.push_back(std::max<std::size_t>(1, (n + count / 2) / count));
  t.plan = {{"input", input_name},
            {"stem", stem},
            {"points", points.size()},
            {"bounding_box_diagonal", canonical_double(points.bounds().diagonal())},
            {"primitives", primitives},
            {"tiles", tiles}};
  t.batch = {{"defaults", {{"primitives", per_tile}, {"no-chain", true}, {"mesh-lods", "none"}, {"no-report-html", true}}},
             {"assets", assets}};
  return t;
}

JoinedSet join_tiles(const nlohmann::json& plan, const std::string& plan_path, const std::string& baked_dir) {
  // 1. The plan's figures (a hand-edited plan fails here, named).
  std::string stem;
  double diagonal = 0;
  std::vector<std::pair<std::string, double>> tiles;  // name, diagonal
  try {
    stem = plan.at("stem").get<std::string>();
    diagonal = plan.at("bounding_box_diagonal").get<double>();
    for (const nlohmann::json& t : plan.at("tiles")) tiles.emplace_back(t.at("name").get<std::string>(), t.at("bounding_box_diagonal").get<double>());
  } catch (const nlohmann::json::exception& e) {
    throw InputError("join.plan", plan_path, "", std::string("not a tile plan of qf-bake tile: ") + e.what());
  }
  if (tiles.empty()) throw InputError("join.plan", plan_path, "", "lists no tiles");
  // 2. Each tile's levels, finest first, from its bake's manifest.
  std::vector<nlohmann::json> levels;
  std::size_t ranks = 0;
  for (const auto& [name, d] : tiles) {
    const std::string folder = baked_dir + "/" + name;
    const nlohmann::json m = read_json(folder + "/manifest.json", "join.tile", "tile " + name + "'s bake (did its task fail?)");
    if (!m.contains("levels") || !m["levels"].is_array() || m["levels"].empty())
      throw InputError("join.tile", folder + "/manifest.json", "", "tile " + name + "'s manifest lists no levels");
    nlohmann::json l = m["levels"];
    std::stable_sort(l.begin(), l.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
      return a.at("primitives").get<std::size_t>() > b.at("primitives").get<std::size_t>();
    });
    ranks = std::max(ranks, l.size());
    levels.push_back(std::move(l));
  }
  // 3. Level r of the set: level r of every tile (or its coarsest) in one file.
  JoinedSet out;
  nlohmann::json set_levels = nlohmann::json::array();
  for (std::size_t r = 0; r < ranks; ++r) {
    std::vector<std::vector<std::uint8_t>> bytes;
    nlohmann::json parts = nlohmann::json::array();
    std::size_t primitives = 0;
    double max_pixels = 1e9;
    for (std::size_t t = 0; t < tiles.size(); ++t) {
      const nlohmann::json& l = levels[t][std::min(r, levels[t].size() - 1)];
      const std::string file = l.at("file").get<std::string>();
      bytes.push_back(read_bytes(baked_dir + "/" + tiles[t].first + "/" + file, "tile " + tiles[t].first + "'s level"));
      parts.push_back(tiles[t].first + "/" + file);
      primitives += l.at("primitives").get<std::size_t>();
      // The tile holds up to M px across its own diagonal d: the whole scan, d/D of it, up to M D / d.
      if (tiles[t].second > 0) max_pixels = std::min(max_pixels, l.at("max_screen_pixels").get<double>() * diagonal / tiles[t].second);
    }
    std::vector<const std::vector<std::uint8_t>*> views;
    for (const auto& b : bytes) views.push_back(&b);
    const std::string name = stem + "_J" + std::to_string(r) + ".glb";
    try {
      out.files.push_back({name, join_glb(views, stem + "_J" + std::to_string(r))});
    } catch (const std::invalid_argument& e) {
      throw InputError("join.tile", baked_dir, "", "level " + std::to_string(r) + " of the tiles: " + e.what());
    }
    set_levels.push_back({{"file", name},
                          {"parts", parts},
                          {"primitives", primitives},
                          {"bytes", out.files.back().bytes.size()},
                          {"max_screen_pixels", std::floor(max_pixels)}});
  }
  out.manifest = {{"input", plan.value("input", "")},
                  {"points", plan.value("points", 0)},
                  {"bounding_box_diagonal", diagonal},
                  {"tiles", tiles.size()},
                  {"levels", set_levels},
                  {"generator", "quasiflat qf-bake join"}};
  return out;
}

}  // namespace qf
