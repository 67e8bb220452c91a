// The bake, as a recipe of named, timed steps (architecture.md): point set -> analysis -> AMG
// hierarchy (cached) -> for each chosen level: basis functions -> domains -> support rectangles
// -> textures -> atlas -> .glb.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "analysis/analysis.h"
#include "domains/domains.h"
#include "domains/merge.h"
#include "gltf/glb.h"
#include "pipeline/out_of_core.h"
#include "primitives/atlas.h"
#include "primitives/support.h"
#include "primitives/texture.h"

namespace qf {

// The hierarchy of a point set, from the cache in `cache_dir` when the points and settings match
// (an empty dir disables the cache), else computed and stored there. `state` says what happened:
// "hit", "miss (<why>)" or "off"; a miss the cache could not store (full, read-only) adds
// ", not saved (<why>)" and the bake goes on without the cache. For a set without normals, `estimated_normals` (if given)
// receives the analysis' oriented normals, from the cache too. `analysed`, when given, is called
// with "analysis" between the analysis and the AMG coarsening of a miss (the bake times them apart).
AmgHierarchy cached_hierarchy(const PointSet& points, const AnalysisOptions& analysis, const AmgOptions& amg,
                              const std::string& cache_dir, std::string& state,
                              std::vector<Vec3f>* estimated_normals = nullptr,
                              const std::function<void(const char*)>& analysed = nullptr);

// The peak memory a bake of `points` points adds to the process that holds them, bytes: a fixed
// part plus, per point, a part for the arrays of every stage and one per neighbour (the
// neighbourhood lists, 8 bytes per neighbour, at their largest during the analysis). Fitted to
// scripts/bench.sh big (peak RSS less the RSS before the bake, default settings): a torus of 1M
// and 10M points added 0.99 and 6.8 GB, bunny00 sampled at LDI 2200 (9.8M points, whose textures
// hold ~3.5x the torus' texels) 8.1 GB; the line bounds the sampled mesh with ~3% to spare and the
// torus with 20-25%. Since then the bake holds its points in Morton order, a copy of 31 bytes a
// point (positions, normals, radii, colours), hence 440 rather than the fitted 400 (10M-point
// torus: 7.90 GB measured, 8.8 GB estimated). The ball mode's extra neighbours are not counted.
constexpr double kBakeBytesPerPoint = 440;
constexpr double kBakeBytesPerNeighbor = 8;
constexpr std::size_t kBakeFixedBytes = std::size_t{384} << 20;
std::size_t estimated_bake_bytes(std::size_t points, const AnalysisOptions& analysis);

struct BakeOptions;

// How a bake fits in memory (plan_bake_memory): in memory when its estimated need fits the limit;
// else, for a point set, out of core (pipeline/out_of_core.h): the decomposition on a subsample
// sized to fit, the textures from every point read back from scratch in tiles.
// A point set's own density can cost more than the even samples the estimate was fitted to: the
// scan-like set (`qf-bake generate scan`, density varying 100-fold) took 1.35x the estimate's
// per-point part in memory at 10M points (11,292 MB peak against 8,379 MB estimated, most of it
// in its AMG hierarchy; at 1M the two shapes cost the same). A point set is planned with that
// margin (its `need`); a mesh's samples are even, and its estimate is used as it is.
constexpr double kPointSetMargin = 1.35;

struct MemoryPlan {
  bool out_of_core = false;
  std::size_t need = 0;        // estimated_bake_bytes of the whole set (a point set's per-point part x kPointSetMargin)
  std::size_t limit = 0;       // bytes: --max-memory, else the memory available
  std::string limit_source;    // "--max-memory", or available_memory's source
  std::size_t subsample = 0;   // out of core: points the decomposition runs on
  std::size_t batch_points = 0;  // out of core: full-density points gathered per batch of quads
  std::size_t sort_points = 0;   // out of core: points sorted in memory at once as they go to scratch
};

// The share of the limit above the fixed part that the out-of-core subsample's decomposition may
// take (at estimated_bake_bytes' rate per point); the rest is for the held hierarchy, each level's
// gathered points (kOutOfCoreBatchShare, at kOutOfCoreBytesPerMember a point and quad) and
// textures.
constexpr double kOutOfCoreSubsampleShare = 0.65;
constexpr double kOutOfCoreBatchShare = 0.15;
// The share the spill's sort may take, at kSpillBytesPerPoint (out_of_core.h): it runs before the
// decomposition, beside nothing but the points' blocks in flight.
constexpr double kOutOfCoreSortShare = 0.5;
// A member: 47 bytes gathered (position, normal, radius, colour, alpha, Psi), up to 10% over its
// quad's reservation, and the texture stage's copies for the quads in hand (index lists and n x 1
// matrices, ~40 bytes). It was 64, counting neither; with that and the Delaunay of every point
// (now merged per cell: texture.cpp), the 100M-point torus passed its 16 GB limit by 2.5 GB.
constexpr double kOutOfCoreBytesPerMember = 96;

// The plan for a bake of `points` points under `max_memory` bytes (0: the memory available,
// core/memory.h available_memory: MemAvailable, the cgroup's limit, QF_MEMORY_LIMIT). Throws
// InputError("bake.memory") naming the estimated need and the limit where no plan fits, so that a
// batch fails that asset with the figures instead of the kernel killing the process: a mesh input
// (`mesh`: its points are sampled, not streamed) past the limit, or a limit too small for a
// subsample of at least max(kOutOfCoreMinSubsample, 16 x the most primitives asked for);
// UsageError for a malformed QF_MEMORY_LIMIT.
constexpr std::size_t kOutOfCoreMinSubsample = 10000;
MemoryPlan plan_bake_memory(std::size_t points, const BakeOptions& options, bool mesh, const std::string& source_name);

struct BakeOptions {
  AnalysisOptions analysis;
  AmgOptions amg;
  BasisOptions basis;
  DomainOptions domains;
  bool merge = false;
  MergeOptions merge_options;
  SupportOptions support;
  TextureOptions texture;
  // Texels per screen pixel where a level is drawn largest (its max_screen_pixels, the bounding-box
  // diagonal's size on screen): each level's texels are sized for its screen size (coarse levels
  // get coarse textures), capped by the point spacing (texture.texel_factor). 0 = from the point
  // spacing alone, at every level. 1, not 2: on the CGAL bunny's vertices, each level drawn at its
  // own max_screen_pixels (engine method, 26 views) scored within 0.03 dB of texels from the point
  // spacing at 1 and within 0.13 dB at 2; the set was 1.53 MB with texels from the points, 1.28 MB
  // at 2, 1.00 MB at 1 (its 18-px level 140, 22, 14 KB).
  double texel_density = 1;
  AtlasOptions atlas;
  GltfOptions gltf;
  // Levels to bake: by number (see level_by_index) or, when empty, the levels nearest these counts
  // of primitives (duplicates removed). The default spans far to middle distances. With merge,
  // the count is of the quads delivered after merging (each candidate level is merged and the
  // one with the nearest merged count is taken, ties to the finer level).
  std::vector<long long> levels;
  std::vector<std::size_t> primitives{1000, 300, 100, 30};
  std::string cache_dir;  // empty = no hierarchy cache
  // The memory the bake may take, bytes (qf-bake --max-memory); 0 = the memory available. Past
  // it a point set bakes out of core (plan_bake_memory).
  std::size_t max_memory = 0;
  std::string scratch_dir;  // the out-of-core bake's scratch file; empty = $TMPDIR, else /tmp
  // Out of core from a stream (the overload taking PointBlocks): outliers are judged there, as the
  // set is never whole in memory (pipeline/out_of_core.h); 0 = none. A set read whole has had its
  // outliers dropped by the loader (pipeline/asset.h load_point_set) and does not use this.
  float outlier_factor = 0.0f;
};

// The quads' alpha edges, cut to the texel where the input's surface ends
// (TextureOptions::edge_cutoff: a ramp on the distance to the support's edge at the alpha cutoff,
// a texel of room around every texture). Without it an edge steps with the texel grid: wavy at
// coarse levels, where a texel spans several point spacings, and on average half a texel outside.
// - A mesh input: alpha stored with exponent 2 (TextureOptions::alpha_exponent) under a cutoff of
//   0.3; a mesh's surface ends at its outermost sampled points, and these edges stay nearer them
//   than Psi at 0.2 does. Engine method, 8 views, the 16 levels of bunny00, fandisk, elephant and
//   the dragon at ~30-1000 quads, summed: +3.7 dB at 64 px and +0.3 dB at 256 px (fandisk's 88
//   quads at 64 px 25.58 -> 26.20 dB), holes within 0.4 points of before. Cutoff 0.35 gained
//   +2.5 / +1.9 dB but opened 0.3-5 points more holes; 0.26 lost 2.1 dB at 256 px. The ramp on
//   top, at 0.7 x the fallback radius past the points (half a spacing, where the sampled surface
//   ends): +4.8 dB at 64 px and +4.2 dB at 256 px, IoU up to +0.025 (fandisk's 88 quads at 64 px
//   26.20 -> 27.18 dB, IoU 0.960 -> 0.967); the overlap method +3.5 / +4.2 dB; holes within 0.5
//   points but at 22-77 quads (elephant and dragon, up to +2 points); bytes +3..10%. Edge radius
//   0.6 gained 0.3 dB more and opened up to 0.5 points more holes; slope 0.4 +0.5 dB at 64 px,
//   with the dragon's 143 quads at 64 px past 2% holes.
//   Since the quads draw the mesh itself (resample_texture's MeshSurface), the coverage of its
//   triangles caps alpha too, so the ramp's radius bounds how far past the outermost points a
//   quad may reach, and the coverage cuts the edge: against the truth (qf-render eval --truth 8,
//   8 views, each level at its own size), the generated tree's four levels at radius 0.7 / 1.0 /
//   1.5 / 2.0 with coverage_gain 2: L6 18.65 / 19.55 / 19.36 / 19.09 dB, IoU 0.728 / 0.781 /
//   0.771 / 0.756 (the old route 18.77, 0.746); gain 1 / 2 / 4 at radius 0.7: 18.43 / 18.65 /
//   18.70 dB. Radius 1.0 and gain 2 cost fandisk 0.5 dB at 682 quads against radius 0.7 and gain
//   1 (36.98 against 37.48 dB; the old route 30.96), bunny00 and the elephant within 0.1 dB.
//   Sparse quads (issue 49; TextureOptions::sparse_fill): quads whose shown texels the surface
//   fills less than 0.7 on average get texels twice min_texel. Fill below 0.7: bunny00 2% and
//   fandisk 0.7% of the quads of their 300- and 30-quad levels, the generated bush 85%, lattice 62%,
//   tree 76%, bare tree 49%. Each default level at its geometric size and half of it (8 views,
//   8x truth, engine method, PNG), coverage of the truth's / PSNR: the tree's 663 quads 0.92 / 20.04
//   dB and 0.54 / 16.66 at half -> 1.07 / 20.95 and 0.96 / 19.33; its 298 quads at half 0.89 ->
//   1.11; the bush's 939 quads at half 0.32 / 15.52 -> 0.58 / 16.68, its 415 at half 0.30 / 16.20
//   -> 0.99 / 18.18; the lattice's 20 quads 0.55 and 0.11 at half -> 1.18 and 0.82; the others
//   within 0.3 dB; bytes 12-40% fewer; bunny00 and fandisk within 0.08 dB and 0.2% of bytes; bake
//   CPU +2..12%. Factor 3 lost up to 1.7 dB at the levels' own size (the tree's 298 quads 20.75 ->
//   19.09), fill 0.8 changed nothing measured. Not kept, tried on the same assets: a hierarchical
//   halftone of coverage on the atlas's mip blocks (exact coverage at the base level, kept at mips
//   1-3) cost 0.5-2.5 dB and 0.05-0.2 soft IoU at both sizes (a dithered beam is binary where the
//   truth is a faint line), and darkening each texel by the spread of its normals (the mean of
//   their facing over its length) cost 0.1-1 dB: the generated tree's and bush's levels average
//   within 3% of the truth's colour already.
// - A point set is drawn as splats, whose edge reaches a radius past its outermost points: Psi
//   stays at cutoff 0.2 (exponent 2 and cutoff 0.3 without the ramp cost the generated torus'
//   finest level 0.3 dB and 0.005 IoU at 256 px), and the ramp cuts a whole fallback radius past
//   the points. The default levels of b9_training, kitten, oni, ball, a 100k-point torus and the
//   octahedron (24 levels, engine method, 8 views), summed: +4.1 dB at 256 px and +3.5 at 64 px;
//   IoU at most 0.009 lower (b9_training at 64 px), oni's +0.02..+0.08; holes up 0.6..2.3 points
//   on b9_training's unevenly scanned ground and 0.3..1.7 on oni's three finer levels, within 0.3
//   elsewhere; bytes +1..4%. The octahedron's merged 8 quads (8k/16k/64k points, seeds 1-3) went
//   from -1.3..+0.4 dB against the metric's floor (a second sampling) to +1.2..+4.3 dB, IoU
//   0.970..0.986 -> 0.989..0.993. Exponent 2 and cutoff 0.3 with the ramp: +4.8 / +6.8 dB, but
//   IoU down to -0.019 (torus, kitten, ball); radius 1.2 / 1.4: +2.0 / +0.8 dB at 256 px, with
//   fewer of b9_training's holes (+0.2..+1.6 points).
inline void use_surface_edges(BakeOptions& o, bool mesh_input) {
  if (mesh_input) {
    o.texture.alpha_exponent = 2;
    o.gltf.alpha_cutoff = 0.3f;
    o.texture.edge_radius = 1.0;
    o.texture.coverage_gain = 2;
    o.texture.sparse_fill = 0.7;
    o.texture.sparse_texel_factor = 2;
  } else {
    o.texture.edge_radius = 1.0;
  }
  o.texture.edge_cutoff = o.gltf.alpha_cutoff;
}

struct BakedLevel {
  std::size_t level = 0;
  std::size_t primitives = 0;
  std::size_t quad_texels = 0;   // texels of the quads' own textures (atlas gutters and padding not counted)
  int atlas_images = 0;
  double error = 0;              // mean of the quads' errors, model units
  double relative_error = 0;     // error / bounding-box diagonal
  // The largest on-screen size of the object (pixels across its bounding-box diagonal) at which the
  // level's mean error stays under half a pixel.
  double max_screen_pixels = 0;
  double texel = 0;  // the smallest texel allowed by the screen size (model units; 0 = no limit)
  std::vector<int> atlas_widths, atlas_heights;  // each atlas image's sides
  std::vector<std::uint8_t> glb;
  TextureCost textures;  // what its textures cost: bytes in the .glb, GPU memory once loaded
};

struct StageTime {
  std::string stage;
  double seconds = 0;
  std::size_t resident_bytes = 0;  // process resident memory at the stage's end (VmRSS)
  std::size_t peak_bytes = 0;      // process peak resident memory so far (VmHWM)
};

struct BakeResult {
  MemoryPlan memory;
  std::uint64_t scratch_bytes = 0;  // out of core: the scratch files at their largest
  std::size_t dropped_outliers = 0;  // out of core from a stream: points judged outliers
  bool streamed = false;             // the points came a block at a time (never whole in memory)
  PointSet subsample;                // out of core from a stream: the points decomposed (the reconstruction's input)
  std::size_t batches = 0;          // out of core: the most batches of quads a level took
  std::vector<BakedLevel> levels;
  std::size_t points = 0, hierarchy_levels = 0, components = 0;
  float diagonal = 0;  // of the bounding box
  std::string cache;   // hit / miss / off
  std::vector<StageTime> times;
  std::vector<std::string> warnings;
};

// --merge with the levels chosen by primitives: the level whose merged basis delivers the number
// of quads nearest each of o.primitives (ties to the finer level), candidates being the levels of
// up to 4 N + 32 functions and the level nearest N before merging. One entry per distinct level,
// in the order of o.primitives; psi is the merged basis (n x quads' columns). `normals` as for
// merge_domains.
struct MergedLevel {
  std::size_t level = 0;
  std::size_t quads = 0;  // non-empty domains of psi
  SparseMatrix psi;
  std::vector<std::array<std::uint32_t, 2>> edges;  // their neighbour graph (MergeReport::edges)
};
std::vector<MergedLevel> choose_merged_levels(const AmgHierarchy& h, const BakeOptions& o, const std::vector<Vec3f>& positions,
                                              const std::vector<Vec3f>& normals);

// Bakes the chosen levels. Throws InputError("bake.too_small") when the set cannot be decomposed
// (fewer points than a neighbourhood needs, or no surface: every fan empty), InputError
// ("bake.memory") when no plan fits the memory (plan_bake_memory, before any work), UsageError
// for a level number the hierarchy does not have. `surface`, for a mesh input (its sampled
// points' triangles, one per point of `points`), gives the quads the mesh's own look
// (resample_texture). Past the memory limit a point set bakes out of core (result.memory says
// so); the overload taking the set by rvalue frees it once written to scratch.
BakeResult bake(const PointSet& points, const BakeOptions& options, const std::string& source_name,
                const MeshSurface* surface = nullptr);
BakeResult bake(PointSet&& points, const BakeOptions& options, const std::string& source_name);
// A point set read a block at a time (io/model_io.h stream_point_set), baked out of core under
// `plan` (plan_bake_memory of the count its header declares; out_of_core). The blocks' errors
// (a reader's InputError) pass through, nothing written but scratch, which is removed.
BakeResult bake(const PointBlocks& blocks, const MemoryPlan& plan, const BakeOptions& options, const std::string& source_name);

}  // namespace qf
