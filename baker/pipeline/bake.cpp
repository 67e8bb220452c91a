// The bake recipe.
#include "pipeline/bake.h"

#include <algorithm>
#include <chrono>

#include "amg/hierarchy_cache.h"
#include "analysis/neighborhoods.h"
#include "core/error.h"
#include "core/memory.h"

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

}  // namespace

AmgHierarchy cached_hierarchy(const PointSet& points, const AnalysisOptions& analysis, const AmgOptions& amg,
                              const std::string& cache_dir, std::string& state, std::vector<Vec3f>* estimated_normals) {
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
  const SurfaceAnalysis a = analyze_surface(points, analysis);
  AmgHierarchy h = build_hierarchy(a.stiffness, amg);
  std::vector<Vec3f> normals;
  if (!points.has_normals()) normals = a.frames.normal;
  if (!cache_dir.empty()) save_hierarchy(cache_dir, key, h, normals);
  if (estimated_normals) *estimated_normals = std::move(normals);
  return h;
}

BakeResult bake(const PointSet& input, const BakeOptions& o, const std::string& source_name) {
  BakeResult r;
  Stopwatch watch(r.times);
  r.points = input.size();
  const std::size_t needed = static_cast<std::size_t>(std::max(4, std::min(o.analysis.neighborhoods.k, 8)));
  if (input.size() < needed)
    throw InputError("bake.too_small", source_name, "",
                     "holds " + std::to_string(input.size()) + " points; a decomposition needs at least " +
                         std::to_string(needed));
  // 1. Complete the point set: radii from spacing where missing; normals stay as given.
  PointSet points = input;
  if (estimate_radii(points) && input.has_radii()) r.warnings.push_back("some radii were 0 and were estimated");
  r.diagonal = points.bounds().diagonal();
  watch.lap("prepare");
  // 2. Hierarchy (analysis + AMG), cached.
  std::vector<Vec3f> estimated;
  const AmgHierarchy h = cached_hierarchy(points, o.analysis, o.amg, o.cache_dir, r.cache, &estimated);
  r.hierarchy_levels = h.level_count();
  r.components = h.components;
  if (h.level_count() < 2)
    throw InputError("bake.too_small", source_name, "",
                     "cannot be decomposed: its " + std::to_string(points.size()) +
                         " points form no surface (all coincident, collinear, or too few)");
  if (h.components > 1)
    r.warnings.push_back(std::to_string(h.components) + " disconnected parts: coarse levels keep one function each");
  watch.lap("hierarchy");
  // Normals orient the planes and make the normal maps: the input's, else the analysis' estimate.
  const std::vector<Vec3f>& normals = points.has_normals() ? points.normals : estimated;
  // 3. Every chosen level: basis, domains, rectangles, textures, atlas, glb.
  const std::vector<std::size_t> levels = chosen_levels(h, o);
  const std::size_t deepest = *std::max_element(levels.begin(), levels.end());
  std::vector<std::pair<std::size_t, SparseMatrix>> bases;
  if (std::find(levels.begin(), levels.end(), std::size_t{0}) != levels.end()) bases.push_back({0, basis_at_level(h, 0)});
  for_each_basis(h, deepest, o.basis, [&](std::size_t l, const SparseMatrix& psi) {
    if (std::find(levels.begin(), levels.end(), l) != levels.end()) bases.push_back({l, psi});
  });
  watch.lap("basis");
  std::vector<ImpostorLevel> kept;  // for the MSFT_lod file
  for (std::size_t level : levels) {
    SparseMatrix psi;
    for (auto& b : bases)
      if (b.first == level) psi = b.second;
    if (o.merge) psi = merge_domains(psi, points.positions, o.merge_options);
    const Domains d = make_domains(psi, o.domains);
    const std::vector<SupportRect> rects = support_rectangles(points.positions, normals, points.radii, psi, d, o.support);
    const SparseMatrix alpha = domain_partition(psi, d);  // what the rendered sum adds up
    watch.lap("level " + std::to_string(level) + " domains");
    std::vector<Texture> textures(rects.size());
#pragma omp parallel for schedule(dynamic, 4)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(rects.size()); ++k)
      textures[static_cast<std::size_t>(k)] = resample_texture(points.positions, points.colors, normals, points.radii, alpha, d,
                                                               rects[static_cast<std::size_t>(k)], o.texture);
    watch.lap("level " + std::to_string(level) + " textures");
    BakedLevel out;
    out.level = level;
    out.primitives = rects.size();
    for (const Texture& t : textures) out.texels += static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
    for (const SupportRect& q : rects) out.error += q.error;
    out.error = rects.empty() ? 0.0 : out.error / double(rects.size());
    out.relative_error = r.diagonal > 0 ? out.error / r.diagonal : 0.0;
    out.max_screen_pixels = out.error > 0 ? std::min(0.5 * r.diagonal / out.error, 1e9) : 1e9;
    ImpostorLevel il = make_impostor_level(level, rects, textures, d, o.atlas);
    out.atlas_images = static_cast<int>(il.atlas.images.size());
    out.glb = encode_glb(il, o.gltf);
    r.levels.push_back(std::move(out));
    if (o.lod_file) kept.push_back(std::move(il));
    watch.lap("level " + std::to_string(level) + " atlas+glb");
  }
  if (o.lod_file) {
    // Finest first. Level i is shown down to the size at which the next coarser one is accurate
    // enough; the coarsest is never culled.
    std::vector<std::size_t> order(kept.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return kept[a].level < kept[b].level; });
    std::vector<const ImpostorLevel*> chain;
    std::vector<double> coverage;
    for (std::size_t i = 0; i < order.size(); ++i) {
      chain.push_back(&kept[order[i]]);
      double c = 0;
      if (i + 1 < order.size()) c = std::min(1.0, r.levels[order[i + 1]].max_screen_pixels / o.lod_screen_height);
      if (!coverage.empty()) c = std::min(c, coverage.back());
      coverage.push_back(canonical_double(static_cast<float>(c)));
    }
    r.lod_glb = encode_lod_glb(chain, coverage, o.gltf);
    watch.lap("lod file");
  }
  return r;
}

}  // namespace qf
