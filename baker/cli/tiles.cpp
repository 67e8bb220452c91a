// The tile and join commands: one scan baked by many machines (pipeline/tiles.h, docs/farm.md).
#include <cstdio>
#include <fstream>

#include "cli/commands.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/output_folder.h"
#include "io/model_io.h"
#include "pipeline/tiles.h"

namespace qf::cli {

CommandSpec tile_spec() {
  return {"tile", "IN -o DIR --tiles N [options]",
          "split one scan into spatial tiles and the batch manifest that bakes them on a farm",
          "Cuts the point set (a mesh is sampled first) across its longest side, recursively, into N tiles of\n"
          "about equal point counts and writes DIR/STEM_t<i>.ply, DIR/tiles.json (the plan: each tile's\n"
          "points and diagonal) and DIR/batch.json (one asset per tile, each aiming at primitives / N quads a\n"
          "level, without chain or mesh LODs). Bake it with qf-bake batch DIR/batch.json -o BAKED (on Slurm:\n"
          "scripts/slurm/bake-array.sbatch, one tile per task), then qf-bake join DIR/tiles.json BAKED -o OUT.",
          {{"output", 'o', "DIR", "", "the folder for the tiles, the plan and the batch manifest; required"},
           {"tiles", 0, "N", "", "number of tiles; required (at most the points / 64)"},
           {"primitives", 0, "N,N,...", "1000,300,100,30", "quads a level of the joined set aims at (divided among the tiles)"},
           drop_nonfinite_option(),
           quiet_option()},
          1, 1};
}

int run_tile(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  const std::string outdir = args.require("output");
  const std::size_t count = static_cast<std::size_t>(args.get_int("tiles", 0, 1, 1 << 20));
  if (!args.has("tiles")) throw UsageError("--tiles N is required");
  std::vector<std::size_t> primitives{1000, 300, 100, 30};
  if (args.has("primitives")) {
    primitives.clear();
    for (long long n : args.get_int_list("primitives", 1, 1ll << 40)) primitives.push_back(static_cast<std::size_t>(n));
  }
  ReadReport report;
  const PointSet points = load_points(in, args, "tile", report);
  const TilePlan plan = plan_tiles(points, in, count, primitives);
  // The folder replaced whole (core/output_folder.h); what else it held is carried over, as before.
  OutputFolder out(outdir);
  out.replace(
      [&](const std::string& staging) {
        for (std::size_t i = 0; i < plan.tiles.size(); ++i) write_ply(staging + "/" + plan.tile_names[i], plan.tiles[i]);
        write_file_atomically(staging + "/batch.json", [&](std::ostream& o) { o << plan.batch.dump(2) << "\n"; });
        write_file_atomically(staging + "/tiles.json", [&](std::ostream& o) { o << plan.plan.dump(2) << "\n"; });
      },
      [](const std::string&) { return true; });
  if (!args.flag("quiet")) {
    std::fprintf(stderr, "qf-bake tile: %s (%zu points) -> %s: %zu tiles of", in.c_str(), points.size(), outdir.c_str(), plan.tiles.size());
    for (const PointSet& t : plan.tiles) std::fprintf(stderr, " %zu", t.size());
    std::fprintf(stderr, " points; bake %s/batch.json, then qf-bake join %s/tiles.json\n", outdir.c_str(), outdir.c_str());
  }
  return 0;
}

CommandSpec join_spec() {
  return {"join", "TILES.json BAKED -o OUT",
          "join the baked tiles of one scan (qf-bake tile, then batch) into one level set",
          "Level r of the set, OUT/STEM_J<r>.glb, draws level r of every tile (finest first; a tile with\n"
          "fewer levels gives its coarsest) as one glTF file, a node per tile (plain glTF: the tiles'\n"
          "QF_impostor_level data stay in their own files). OUT/manifest.json lists each level's parts,\n"
          "primitives, bytes and max_screen_pixels (the smallest of the tiles', scaled to the whole scan).\n"
          "A tile whose bake is missing or broken is named, and nothing is written.",
          {{"output", 'o', "OUT", "", "the joined level set's folder; required"}, quiet_option()},
          2, 2};
}

int run_join(const ParsedArgs& args) {
  const std::string& plan_path = args.positional[0];
  const std::string& baked = args.positional[1];
  const std::string outdir = args.require("output");
  nlohmann::json plan;
  {
    const InputFile f(plan_path);
    const ByteView b = f.bytes();
    try {
      plan = nlohmann::json::parse(b.data(), b.data() + b.size());
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError("join.plan", plan_path, "", std::string("not valid JSON: ") + e.what());
    }
  }
  const JoinedSet set = join_tiles(plan, plan_path, baked);
  OutputFolder out(outdir);
  write_asset(out, set.files, set.manifest, nullptr);
  if (!args.flag("quiet")) {
    std::fprintf(stderr, "qf-bake join: %zu tiles -> %s:", set.manifest["tiles"].get<std::size_t>(), outdir.c_str());
    for (const nlohmann::json& l : set.manifest["levels"])
      std::fprintf(stderr, " %s (%zu primitives)", l["file"].get<std::string>().c_str(), l["primitives"].get<std::size_t>());
    std::fprintf(stderr, "\n");
  }
  return 0;
}

}  // namespace qf::cli
