// One scan too big for one machine, baked by many (docs/farm.md, "One scan over many machines"):
// `qf-bake tile` splits it into spatial tiles and writes them with a batch manifest, the farm bakes
// the batch (a Slurm array's tasks, scripts/slurm), and `qf-bake join` joins the tiles' levels into
// one level set.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "pipeline/asset.h"

namespace qf {

// The points of each of `count` spatial tiles of about equal point counts: the set is cut across
// its longest side at the point that splits the count in proportion to the tiles on each side,
// recursively (a k-d split; the lower side first). Indices ascending within a tile. Deterministic.
std::vector<std::vector<std::uint32_t>> spatial_tiles(const std::vector<Vec3f>& positions, std::size_t count);

struct TilePlan {
  nlohmann::json plan;                   // tiles.json: the input, its diagonal, each tile's name, file, points, diagonal
  nlohmann::json batch;                  // batch.json: one asset per tile, primitives divided among the tiles
  std::vector<std::string> tile_names;   // STEM_t<i>.ply, in the plan's order
  std::vector<PointSet> tiles;
};

// The tiles of `points` (read from `input_name`, named after its stem) as point sets to write as
// PLY files beside the plan and the batch manifest that bakes them (paths relative to that folder). Each tile's bake aims at primitives / count quads a
// level (at least 1), so that the joined levels hold about `primitives`; the tiles' bakes skip
// the chain and mesh LODs (the join makes neither). UsageError when count is 0 or exceeds the
// points / 64.
TilePlan plan_tiles(const PointSet& points, const std::string& input_name, std::size_t count,
                    const std::vector<std::size_t>& primitives);

// The joined level set of the tiles baked under `baked_dir` (the batch's output: one folder per
// tile, named as in the plan): level r of the set (STEM_J<r>.glb) draws level r of every tile
// (their manifests' order, finest first; a tile with fewer levels gives its coarsest), and the
// manifest says per level its parts, primitives, bytes and max_screen_pixels (the smallest over the
// tiles, each scaled from its own diagonal to the whole scan's). Throws InputError("join.tile") naming
// the tile whose bake is missing or broken, ("join.plan") for a plan that does not parse.
struct JoinedSet {
  std::vector<OutputFile> files;
  nlohmann::json manifest;
};
JoinedSet join_tiles(const nlohmann::json& plan, const std::string& plan_path, const std::string& baked_dir);

}  // namespace qf
