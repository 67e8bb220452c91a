// The out-of-core bake's streaming parts (issue 35 items 1-2): a point set too big for the memory
// at hand comes a block at a time (from a streaming reader, io/model_io.h stream_point_set, or
// from memory) and is written to a scratch file in spatial (Morton) tiles, sorted on disk; the
// decomposition runs on an even subsample that fits, and every level's textures are then
// resampled from every point, read back tile by tile. pipeline/bake.cpp chooses the path
// (plan_bake_memory) and runs the recipe; this file holds what streams.
//
// Outliers (ReadOptions::outlier_factor) are judged as the whole set is not there to judge them
// by: the subsample's own outliers go before its decomposition (drop_subsample_outliers: the
// in-memory rule on the subsample), then a full point goes when its links reach farther than that
// rule's limit on the subsample's spacing (link_points: it takes no part in any texture).
//
// How a full-density point takes part in a level decomposed on the subsample: it is linked to its
// kLinks nearest subsample points with inverse-square-distance weights summing to 1 (link_points),
// and its basis functions are the weighted sum of theirs: Psi_full = W Psi_sub, W n x m,
// non-negative, rows summing to 1, so Psi_full stays a partition of unity (one more prolongation,
// as the AMG's own). Its domains and alpha then follow the in-memory rules (domains.h: Psi > tau,
// or the strongest function with --strict; alpha renormalised over its domains).
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/scratch.h"
#include "core/sparse.h"
#include "core/types.h"
#include "domains/domains.h"
#include "primitives/support.h"
#include "primitives/texture.h"

namespace qf {

constexpr int kLinks = 4;                     // subsample points each full point is linked to
constexpr std::size_t kTilePoints = 1u << 16;  // points per tile of the scratch file (~2 MB)

// The full point set on disk and its subsample in memory.
struct StreamedPoints {
  struct Tile {
    std::uint64_t offset = 0;        // of its records in the file (positions, then normals, radii, colours)
    std::uint64_t links_offset = 0;  // of its links (indices, then weights), once linked
    std::uint32_t first = 0, count = 0;  // its points, in the full set's Morton order
    Bounds bounds;
    float reach = 0;                 // farthest link of its points (world units)
  };
  std::unique_ptr<ScratchFile> file;
  std::vector<Tile> tiles;
  std::size_t points = 0;
  bool normals = false, radii = false, colors = false;  // what a record holds
  bool needs_radii = false;  // some radii absent or 0: those come from the subsample's (links)
  Bounds bounds;
  std::uint64_t scratch_peak = 0;  // bytes of scratch at the spill's largest (its sort's files)
  float outlier_limit = INFINITY;  // a full point farther from its links than this is an outlier
  // One point per stratum of `stride` consecutive points of the Morton order (the one nearest the
  // stratum's centroid), in Morton order; its radii are at the full set's density.
  PointSet subsample;
  double stride = 1;
};

// A point set a block at a time: calls `each` with every block in turn (which may take its arrays).
using PointBlocks = std::function<void(const std::function<void(PointSet&)>& each)>;
// A set in memory as blocks of kTilePoints (copies).
PointBlocks blocks_of(const PointSet& points);

struct SpillOptions {
  std::size_t subsample = 1;    // points the decomposition runs on (at most the set's)
  std::size_t sort_points = 1;  // points sorted in memory at once (kSpillBytesPerPoint each)
  std::string scratch_dir;      // empty: $TMPDIR, else /tmp
};
// What sorting takes a point: its records (31 bytes) and their sorted copy, or its key (32 bytes),
// its place in the order and its code and index (20), with room to spare.
constexpr double kSpillBytesPerPoint = 96;

// Writes the points `blocks` hands over to a scratch file in Morton order, the order
// morton_order gives the whole set (an external sort: the blocks as they come to a scratch file,
// then runs of sort_points sorted in memory, then merged), and picks the subsample on the way.
// Radii missing or 0 in the input are estimated for the subsample from its own spacing, scaled to
// the full density (spacing goes as 1/sqrt(density) on a surface: / sqrt(stride)). The same
// bytes whatever the blocks' sizes, the sort_points and the thread count. Throws
// std::runtime_error where the disk is full; what the blocks throw (a reader's error) passes,
// every scratch file removed.
StreamedPoints spill_points(const PointBlocks& blocks, const SpillOptions& options);

// The subsample's outliers (analysis/neighborhoods.h find_outliers at `factor`; 0: none) erased
// from it; their limit kept as s.outlier_limit for link_points. Returns how many went.
std::size_t drop_subsample_outliers(StreamedPoints& s, float factor);

// Links every point of the file to its kLinks nearest subsample points (ties by index), written to
// the file beside the points; every tile's reach recorded. A point whose links' mean distance
// passes s.outlier_limit is linked to nothing (weights 0: in no domain, no texture). Returns how
// many were.
std::size_t link_points(StreamedPoints& s);

// A level's textures, one per rectangle (rects' order), resampled from every point: `psi` is the
// level's basis on the subsample (m x functions), `d` its domains there, `rects` their rectangles
// there, remade here from every point of each domain (support_rectangles with `support`: the
// plane, the extent that holds every splat, the mean radius) as the in-memory bake makes them;
// `sub_normals` the subsample's normals (the input's or estimated; full points without normals
// get their links'). Quads are handled in batches of about `batch_points` full-density points
// each, every batch reading the tiles that may reach its quads. `batches`, when given, gets their
// number. The same bytes at any thread count and any batch size.
std::vector<Texture> streamed_textures(const StreamedPoints& s, const std::vector<Vec3f>& sub_normals, const SparseMatrix& psi,
                                       const Domains& d, std::vector<SupportRect>& rects, const DomainOptions& domains,
                                       const SupportOptions& support, const TextureOptions& texture, std::size_t batch_points,
                                       std::size_t* batches = nullptr);

}  // namespace qf
