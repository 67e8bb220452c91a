// The bake recipe.
#include "pipeline/bake.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "amg/hierarchy_cache.h"
#include "analysis/neighborhoods.h"
#include "core/error.h"
#include "core/memory.h"
#include "core/progress.h"
#include "pipeline/out_of_core.h"
#include "measure/screen_sizes.h"

namespace qf {
namespace {

class Stopwatch {
 public:
  explicit Stopwatch(std::vector<StageTime>& out) : out_(out), t_(std::chrono::steady_clock::now()) {}
  void lap(const std::string& stage) {
    const auto now = std::chrono::steady_clock::now();
    out_.push_back({stage, std::chrono::duration<double>(now - t_).count(), process_memory("VmRSS:"), process_memory("VmHWM:")});
    t_ = now;
  }

 private:
  std::vector<StageTime>& out_;
  std::chrono::steady_clock::time_point t_;
};

// The levels to bake, coarse to fine order of the options, without repeats.
std::vector<std::size_t> chosen_levels(const AmgHierarchy& h, const BakeOptions& o) {
  std::vector<std::size_t> out;
  if (!o.levels.empty())
    for (long long k : o.levels) {
      try {
        out.push_back(level_by_index(h, k));
      } catch (const std::out_of_range& e) {  // a setting, not the input, is wrong
        throw UsageError(std::string("--levels: ") + e.what());
      }
    }
  else
    for (std::size_t n : o.primitives) out.push_back(level_by_primitives(h, n));
  std::vector<std::size_t> unique;
  for (std::size_t l : out)
    if (std::find(unique.begin(), unique.end(), l) == unique.end()) unique.push_back(l);
  return unique;
}

// The texture options of a level drawn at most `max_screen_pixels` across the bounding-box
// diagonal: there one screen pixel is diagonal / max_screen_pixels wide, and its texels are
// texel_density times finer (but never finer than the points, TextureOptions::texel_factor).
// Texels sized for the points alone gave a 16-px level of the bunny 65k texels. No level is shown
// above the largest size the measuring draws (kLargestMeasuredPixels): a textured cube's levels,
// made by their geometry for 43,913-114,569 px, took 3.2-4.1M texels each and 28 s.
TextureOptions level_texture_options(const BakeOptions& o, double diagonal, double max_screen_pixels) {
  TextureOptions t = o.texture;
  max_screen_pixels = std::min(max_screen_pixels, double(kLargestMeasuredPixels));
  if (o.texel_density > 0 && max_screen_pixels > 0) t.min_texel = diagonal / (max_screen_pixels * o.texel_density);
  return t;
}

// Every quad's texture (resample_texture), largest domains first, one at a time: a coarse level
// has a few big domains, and handed out in index order, in fours, one thread was left with most of
// the work. Each texture depends on its domain alone, so the order changes no byte.
std::vector<Texture> level_textures(const PointSet& points, const std::vector<Vec3f>& normals, const SparseMatrix& alpha,
                                    const Domains& d, const std::vector<SupportRect>& rects, const TextureOptions& texture,
                                    const MeshSurface* surface) {
  std::vector<std::size_t> by_size(rects.size());
  for (std::size_t k = 0; k < by_size.size(); ++k) by_size[k] = k;
  const auto domain_points = [&](std::size_t k) { return d.offsets[rects[k].domain + 1] - d.offsets[rects[k].domain]; };
  std::stable_sort(by_size.begin(), by_size.end(), [&](std::size_t a, std::size_t b) { return domain_points(a) > domain_points(b); });
  std::vector<Texture> textures(rects.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t q = 0; q < static_cast<std::ptrdiff_t>(by_size.size()); ++q) {
    const std::size_t k = by_size[static_cast<std::size_t>(q)];
    textures[k] = resample_texture(points.positions, points.colors, normals, points.radii, alpha, d, rects[k], texture, surface);
    progress::advance();
  }
  return textures;
}

}  // namespace

// --merge with --primitives counts the quads delivered, after merging: every level of up to
// kMergeCandidates x N + 32 functions (and the level nearest N before merging) is merged, and the
// one whose merged domain count is nearest N wins, ties to the finer level (measured on the
// octahedron and cube, 8k-64k points, seeds 1-6: every level from ~3x the faces to ~50 functions
// merges into one domain per face, the coarser ones into fewer, spanning two faces; the level
// nearest N before merging gave 5 or 7 quads for 8). A cap, not every level: the finest levels
// merge into the same domains at many times the cost.
constexpr std::size_t kMergeCandidates = 4;

std::vector<MergedLevel> choose_merged_levels(const AmgHierarchy& h, const BakeOptions& o, const std::vector<Vec3f>& positions,
                                              const std::vector<Vec3f>& normals) {
  const std::size_t wants = o.primitives.size();
  std::vector<std::size_t> nearest;
  for (std::size_t n : o.primitives) nearest.push_back(level_by_primitives(h, n));
  auto candidate = [&](std::size_t k, std::size_t level) {
    return level == nearest[k] || (level > 0 && h.levels[level].size <= kMergeCandidates * o.primitives[k] + 32);
  };
  std::vector<MergedLevel> best(wants);
  std::vector<char> set(wants, 0);
  auto consider = [&](std::size_t level, const SparseMatrix& raw) {
    bool wanted = false;
    for (std::size_t k = 0; k < wants; ++k) wanted |= candidate(k, level);
    if (!wanted) return;
    MergeReport report;
    SparseMatrix merged = merge_domains(raw, positions, normals, o.merge_options, &report);
    const std::size_t count = count_domains(merged, o.domains);
    for (std::size_t k = 0; k < wants; ++k) {
      if (!candidate(k, level)) continue;
      const auto gap = [&](std::size_t c) { return c > o.primitives[k] ? c - o.primitives[k] : o.primitives[k] - c; };
      MergedLevel& b = best[k];
      if (set[k] && (gap(count) > gap(b.quads) || (gap(count) == gap(b.quads) && level > b.level))) continue;
      b = {level, count, merged, report.edges};
      set[k] = 1;
    }
  };
  bool level0 = false;
  for (std::size_t k = 0; k < wants; ++k) level0 |= candidate(k, 0);
  if (level0) consider(0, basis_at_level(h, 0));
  for_each_basis(h, h.level_count() - 1, o.basis, consider);  // fine to coarse
  std::vector<MergedLevel> out;
  for (MergedLevel& b : best) {
    bool seen = false;
    for (const MergedLevel& u : out) seen |= u.level == b.level;
    if (!seen) out.push_back(std::move(b));
  }
  return out;
}

AmgHierarchy cached_hierarchy(const PointSet& points, const AnalysisOptions& analysis, const AmgOptions& amg,
                              const std::string& cache_dir, std::string& state, std::vector<Vec3f>* estimated_normals,
                              const std::function<void(const char*)>& analysed) {
  const std::string key = hierarchy_cache_key(points, analysis, amg);
  if (!cache_dir.empty()) {
    std::string why;
    std::vector<Vec3f> normals;
    if (std::optional<AmgHierarchy> h = load_hierarchy(cache_dir, key, &why, &normals)) {
      state = "hit";
      if (estimated_normals) *estimated_normals = std::move(normals);
      return std::move(*h);
    }
    state = "miss (" + why + ")";
  } else {
    state = "off";
  }
  // The lean analysis: its intermediates are gone before the matrix is built, and the matrix is
  // handed over to the hierarchy, which frees it once renumbered.
  SurfaceAnalysis a = analyze_surface(points, analysis, AnalysisKeep::kStiffnessAndNormals);
  std::vector<Vec3f> normals;
  if (!points.has_normals()) normals = std::move(a.frames.normal);
  SparseMatrix stiffness = std::move(a.stiffness);
  a = SurfaceAnalysis{};
  if (analysed) analysed("analysis");
  AmgHierarchy h = build_hierarchy(std::move(stiffness), amg);
  if (!cache_dir.empty()) {
    // A cache that cannot take the entry (full, read-only, not a folder) costs the next bake its
    // reuse, not this bake: said in the state, and the caller warns.
    try {
      save_hierarchy(cache_dir, key, h, normals);
    } catch (const std::exception& e) {
      state += ", not saved (" + std::string(e.what()) + ")";
    }
  }
  if (estimated_normals) *estimated_normals = std::move(normals);
  return h;
}

std::size_t estimated_bake_bytes(std::size_t points, const AnalysisOptions& analysis) {
  const double per_point = kBakeBytesPerPoint + kBakeBytesPerNeighbor * std::max(1, analysis.neighborhoods.k);
  return kBakeFixedBytes + static_cast<std::size_t>(per_point * double(points));
}

MemoryPlan plan_bake_memory(std::size_t points, const BakeOptions& o, bool mesh, const std::string& source_name) {
  MemoryPlan plan;
  plan.need = estimated_bake_bytes(points, o.analysis);
  if (!mesh) plan.need = kBakeFixedBytes + static_cast<std::size_t>(kPointSetMargin * double(plan.need - kBakeFixedBytes));
  if (o.max_memory > 0) {
    plan.limit = o.max_memory, plan.limit_source = "--max-memory";
  } else {
    MemoryBudget budget;
    try {
      budget = available_memory();
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("QF_MEMORY_LIMIT: ") + e.what());
    }
    plan.limit = budget.bytes, plan.limit_source = budget.source;
  }
  if (plan.need <= plan.limit) return plan;
  const std::string figures = "its " + std::to_string(points) + " points need about " + format_bytes(double(plan.need)) +
                              " to bake (estimated), but only " + format_bytes(double(plan.limit)) + " is " +
                              (o.max_memory > 0 ? "allowed" : "available") + " (" + plan.limit_source + ")";
  if (mesh)
    throw InputError("bake.memory", source_name, "",
                     figures + "; a mesh is sampled into points and baked in memory, not streamed: sample fewer points (--ldi), "
                               "or bake it on a machine with more memory");
  // Out of core: the largest subsample whose decomposition takes its share of the limit.
  const double per_point = kBakeBytesPerPoint + kBakeBytesPerNeighbor * std::max(1, o.analysis.neighborhoods.k);
  const double room = plan.limit > kBakeFixedBytes ? double(plan.limit - kBakeFixedBytes) : 0.0;
  const auto fits = static_cast<std::size_t>(kOutOfCoreSubsampleShare * room / per_point);
  std::size_t most = 0;
  for (std::size_t n : o.primitives) most = std::max(most, n);
  const std::size_t least = std::max(kOutOfCoreMinSubsample, 16 * (o.levels.empty() ? most : 0));
  if (fits < least)
    throw InputError("bake.memory", source_name, "",
                     figures + "; even out of core, a subsample of " + std::to_string(least) + " points needs about " +
                         format_bytes(kBakeFixedBytes + double(least) * per_point / kOutOfCoreSubsampleShare) +
                         "; bake it on a machine with more memory, or split it");
  plan.out_of_core = true;
  plan.subsample = std::min(points, fits);
  plan.batch_points = std::max<std::size_t>(1, static_cast<std::size_t>(kOutOfCoreBatchShare * room / kOutOfCoreBytesPerMember));
  plan.sort_points = std::max(kTilePoints, static_cast<std::size_t>(kOutOfCoreSortShare * room / kSpillBytesPerPoint));
  return plan;
}

namespace {

// 2. Complete the point set: a copy in Morton order, radii from spacing where missing; normals
//    stay as given. Morton order because every later stage reads points beside their neighbours
//    (on shuffled input the analysis, bases and textures were bound by cache misses), and it makes
//    a reordered file bake to the same files (unless two of its points share a position exactly).
PointSet completed_points(const PointSet& input, const std::vector<std::uint32_t>& order, BakeResult& r) {
  PointSet points = permuted(input, order);
  const bool needs_radii = !points.has_radii() || std::find(points.radii.begin(), points.radii.end(), 0.0f) != points.radii.end();
  if (needs_radii && estimate_radii(points) && input.has_radii()) r.warnings.push_back("some radii were 0 and were estimated");
  return points;
}

// A level's textures from its basis on the bake's points, its domains and rectangles: the
// out-of-core bake resamples them from every point on disk (streamed_textures) instead of from
// the subsample the level was decomposed on.
// It may remake the rectangles (from every point), which the level's quads then take.
using LevelTexturer = std::function<std::vector<Texture>(const SparseMatrix& psi, const Domains& d,
                                                         std::vector<SupportRect>& rects, const TextureOptions& texture)>;

// 4b. One level from its basis `psi` (with --merge, merged, and its neighbour edges): domains,
// rectangles, textures (`texturer`'s when given), atlas, glb.
BakedLevel bake_level(std::size_t level, const SparseMatrix& psi, std::vector<std::array<std::uint32_t, 2>> merged_edges,
                      const PointSet& points, const std::vector<Vec3f>& normals, const BakeOptions& o, double diagonal,
                      const MeshSurface* surface, Stopwatch& watch, const LevelTexturer* texturer) {
  const std::string name = "level " + std::to_string(level);
  progress::step(name + ": domains and rectangles");
  Domains d = make_domains(psi, o.domains);
  // Merged faces trimmed at their crease no longer overlap but stay neighbours there.
  if (o.merge) d.edges = std::move(merged_edges);
  std::vector<SupportRect> rects = support_rectangles(points.positions, normals, points.radii, psi, d, o.support);
  SparseMatrix alpha = texturer ? SparseMatrix() : domain_partition(psi, d);  // what the rendered sum adds up
  watch.lap(name + " domains");
  BakedLevel out;
  out.level = level;
  out.primitives = rects.size();
  for (const SupportRect& q : rects) out.error += q.error;
  out.error = rects.empty() ? 0.0 : out.error / double(rects.size());
  out.relative_error = diagonal > 0 ? out.error / diagonal : 0.0;
  out.max_screen_pixels = out.error > 0 ? std::min(0.5 * diagonal / out.error, 1e9) : 1e9;
  const TextureOptions texture = level_texture_options(o, diagonal, out.max_screen_pixels);
  out.texel = texture.min_texel;
  progress::step(name + ": textures of " + std::to_string(rects.size()) + " quads", rects.size());
  std::vector<Texture> textures =
      texturer ? (*texturer)(psi, d, rects, texture) : level_textures(points, normals, alpha, d, rects, texture, surface);
  watch.lap(name + " textures");
  for (const Texture& t : textures) out.quad_texels += static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
  // The level's partition is done with; its textures once packed into the atlas (at 10M sampled
  // points a level's textures are ~0.8 GB, freed before the PNG encoding needs more).
  alpha = SparseMatrix();
  ImpostorLevel il = make_impostor_level(level, rects, textures, d, o.atlas);
  il.alpha_exponent = texture.alpha_exponent;
  std::vector<Texture>().swap(textures);
  out.atlas_images = static_cast<int>(il.atlas.images.size());
  out.atlas_widths = il.atlas.widths, out.atlas_heights = il.atlas.heights;
  progress::step(name + ": atlas and .glb");
  GltfOptions gltf = o.gltf;
  gltf.threads = omp_get_max_threads();  // the KTX2 encoder's job pool: levels are encoded one at a time
  out.glb = encode_glb(il, gltf, &out.textures);
  watch.lap(name + " atlas+glb");
  return out;
}

// 4. Every chosen level, in the order of choice. Each is baked as soon as its basis is made, from
// the hierarchy walk's own matrix: no basis is copied or held past its level (at 10M points the
// four default levels' copies held 1.7 GB until the last was baked). With --merge, levels chosen
// by their merged count come merged from choose_merged_levels.
std::vector<BakedLevel> baked_levels(const AmgHierarchy& h, const BakeOptions& o, const PointSet& points,
                                     const std::vector<Vec3f>& normals, double diagonal, const MeshSurface* surface,
                                     Stopwatch& watch, const LevelTexturer* texturer = nullptr) {
  std::vector<BakedLevel> out;
  progress::step("basis functions");
  if (o.merge && o.levels.empty()) {
    std::vector<MergedLevel> bases = choose_merged_levels(h, o, points.positions, normals);
    watch.lap("basis");
    for (MergedLevel& b : bases) {
      out.push_back(bake_level(b.level, b.psi, std::move(b.edges), points, normals, o, diagonal, surface, watch, texturer));
      b.psi = SparseMatrix();  // done with
    }
    return out;
  }
  const std::vector<std::size_t> levels = chosen_levels(h, o);
  const auto wanted = [&](std::size_t l) { return std::find(levels.begin(), levels.end(), l) != levels.end(); };
  const auto visit = [&](std::size_t l, const SparseMatrix& psi) {
    if (!wanted(l)) return;
    if (!o.merge) {
      watch.lap("level " + std::to_string(l) + " basis");
      out.push_back(bake_level(l, psi, {}, points, normals, o, diagonal, surface, watch, texturer));
      progress::step("basis functions");
      return;
    }
    MergeReport report;
    const SparseMatrix merged = merge_domains(psi, points.positions, normals, o.merge_options, &report);
    watch.lap("level " + std::to_string(l) + " basis");
    out.push_back(bake_level(l, merged, std::move(report.edges), points, normals, o, diagonal, surface, watch, texturer));
    progress::step("basis functions");
  };
  if (wanted(0)) visit(0, basis_at_level(h, 0));
  for_each_basis(h, *std::max_element(levels.begin(), levels.end()), o.basis, visit);
  std::vector<BakedLevel> ordered;
  for (std::size_t l : levels)
    for (BakedLevel& b : out)
      if (b.level == l) {
        ordered.push_back(std::move(b));
        break;
      }
  if (ordered.size() != levels.size()) throw std::logic_error("bake: a chosen level had no basis");
  return ordered;
}

}  // namespace

namespace {

// 3. Hierarchy (analysis + AMG) of the points the decomposition runs on, cached; estimated
// normals into `estimated` where the points have none.
AmgHierarchy decomposed(const PointSet& points, const BakeOptions& o, const std::string& source_name, BakeResult& r,
                        Stopwatch& watch, std::vector<Vec3f>& estimated) {
  progress::step("analysis (neighbourhoods, classifier, stiffness)");
  AmgHierarchy h = cached_hierarchy(points, o.analysis, o.amg, o.cache_dir, r.cache, &estimated, [&](const char* stage) {
    watch.lap(stage);
    progress::step("AMG coarsening");
  });
  if (r.cache.find(", not saved (") != std::string::npos)
    r.warnings.push_back("the AMG cache " + o.cache_dir + " could not be written, baked without it: " + r.cache);
  r.hierarchy_levels = h.level_count();
  r.components = h.components;
  if (h.level_count() < 2)
    throw InputError("bake.too_small", source_name, "",
                     "cannot be decomposed: its " + std::to_string(points.size()) +
                         " points form no surface (all coincident, collinear, or too few)");
  if (h.components > 1)
    r.warnings.push_back(std::to_string(h.components) + " disconnected parts: coarse levels keep one function each");
  watch.lap("hierarchy");
  return h;
}

// The in-memory bake: every stage on every point.
void bake_in_memory(const PointSet& input, const BakeOptions& o, const std::string& source_name, const MeshSurface* surface,
                    BakeResult& r, Stopwatch& watch) {
  // 2. Complete the point set; a mesh surface's triangles follow its points into Morton order.
  progress::step("ordering " + std::to_string(input.size()) + " points");
  std::vector<std::uint32_t> order = morton_order(input.positions);
  const PointSet points = completed_points(input, order, r);
  MeshSurface ordered_surface;
  if (surface && surface->mesh) {
    if (surface->point_triangles.size() != input.size()) throw std::logic_error("bake: a mesh surface needs one triangle per point");
    ordered_surface.mesh = surface->mesh;
    ordered_surface.normals = surface->normals;
    ordered_surface.point_triangles.resize(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) ordered_surface.point_triangles[i] = surface->point_triangles[order[i]];
  }
  std::vector<std::uint32_t>().swap(order);  // not held through the bake (4 bytes a point)
  const MeshSurface* drawn = ordered_surface.mesh ? &ordered_surface : nullptr;
  r.diagonal = points.bounds().diagonal();
  watch.lap("prepare");
  // 3. Hierarchy (analysis + AMG), cached.
  std::vector<Vec3f> estimated;
  const AmgHierarchy h = decomposed(points, o, source_name, r, watch, estimated);
  // Normals orient the planes and make the normal maps: the input's, else the analysis' estimate.
  const std::vector<Vec3f>& normals = points.has_normals() ? points.normals : estimated;
  // 4. Every chosen level: basis, then domains, rectangles, textures, atlas, glb.
  r.levels = baked_levels(h, o, points, normals, r.diagonal, drawn, watch);
}

// The out-of-core bake (pipeline/out_of_core.h): the points to scratch in Morton tiles, the
// decomposition on the subsample, each level's textures from every point read back tile by tile.
// `spilled` is called once the points are on disk (a set in memory is freed then).
void bake_out_of_core(const PointBlocks& blocks, const BakeOptions& o, const std::string& source_name, BakeResult& r,
                      Stopwatch& watch, const std::function<void()>& spilled = nullptr) {
  // 2. Scratch and subsample; the subsample's outliers.
  StreamedPoints s;
  try {
    s = spill_points(blocks, {r.memory.subsample, r.memory.sort_points, o.scratch_dir});
  } catch (const InputError&) {
    throw;  // the reader's
  } catch (const std::runtime_error& e) {  // no room on disk: the setting or the machine, not the input
    throw UsageError(std::string("out-of-core bake: ") + e.what());
  }
  if (spilled) spilled();
  if (s.needs_radii && s.radii) r.warnings.push_back("some radii were 0 and were estimated");
  r.points = s.points;
  r.diagonal = s.bounds.diagonal();
  if (o.outlier_factor > 0) {
    progress::step("outliers of the subsample of " + std::to_string(s.subsample.size()) + " points");
    drop_subsample_outliers(s, o.outlier_factor);
  }
  watch.lap("spill");
  // 3. Hierarchy of the subsample; every point linked to it.
  std::vector<Vec3f> estimated;
  const AmgHierarchy h = decomposed(s.subsample, o, source_name, r, watch, estimated);
  const std::vector<Vec3f>& normals = s.subsample.has_normals() ? s.subsample.normals : estimated;
  try {
    r.dropped_outliers = link_points(s);
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("out-of-core bake: ") + e.what());
  }
  r.points -= r.dropped_outliers;
  watch.lap("link");
  // 4. Every chosen level, decomposed on the subsample, textured from every point.
  const LevelTexturer streamed = [&](const SparseMatrix& psi, const Domains& d, std::vector<SupportRect>& rects,
                                     const TextureOptions& texture) {
    std::size_t batches = 0;
    std::vector<Texture> t =
        streamed_textures(s, normals, psi, d, rects, o.domains, o.support, texture, r.memory.batch_points, &batches);
    r.batches = std::max(r.batches, batches);
    return t;
  };
  r.levels = baked_levels(h, o, s.subsample, normals, r.diagonal, nullptr, watch, &streamed);
  r.scratch_bytes = std::max<std::uint64_t>(s.scratch_peak, s.file->size());
  r.subsample = std::move(s.subsample);
}

BakeResult bake_points(const PointSet& input, PointSet* owned, const BakeOptions& o, const std::string& source_name,
                       const MeshSurface* surface) {
  BakeResult r;
  Stopwatch watch(r.times);
  r.points = input.size();
  const std::size_t needed = static_cast<std::size_t>(std::max(4, std::min(o.analysis.neighborhoods.k, 8)));
  if (input.size() < needed)
    throw InputError("bake.too_small", source_name, "",
                     "holds " + std::to_string(input.size()) + " points; a decomposition needs at least " +
                         std::to_string(needed));
  // 1. The path that fits in memory; a failure early, with the figures, where none does (not an
  //    OOM kill).
  r.memory = plan_bake_memory(input.size(), o, surface && surface->mesh, source_name);
  if (!r.memory.out_of_core) {
    bake_in_memory(input, o, source_name, surface, r, watch);
    return r;
  }
  BakeOptions read_whole = o;
  read_whole.outlier_factor = 0;  // a set read whole had its outliers dropped as it was loaded
  bake_out_of_core(blocks_of(input), read_whole, source_name, r, watch, [&] {
    if (owned) *owned = PointSet();  // on disk now; its memory goes to the decomposition
  });
  r.subsample = PointSet();
  return r;
}

}  // namespace

BakeResult bake(const PointSet& input, const BakeOptions& o, const std::string& source_name, const MeshSurface* surface) {
  return bake_points(input, nullptr, o, source_name, surface);
}

BakeResult bake(PointSet&& input, const BakeOptions& o, const std::string& source_name) {
  return bake_points(input, &input, o, source_name, nullptr);
}

BakeResult bake(const PointBlocks& blocks, const MemoryPlan& plan, const BakeOptions& o, const std::string& source_name) {
  if (!plan.out_of_core) throw std::logic_error("bake: a stream of points is baked out of core");
  BakeResult r;
  Stopwatch watch(r.times);
  r.memory = plan;
  r.streamed = true;
  bake_out_of_core(blocks, o, source_name, r, watch);
  return r;
}

}  // namespace qf
