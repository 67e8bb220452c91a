// One asset end to end: read (and sample a mesh), bake the impostor levels, add the mesh-only
// outputs, and describe it all in a manifest and a report.
#include "pipeline/asset.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <functional>
#include <limits>
#include <map>
#include <set>

#include "analysis/neighborhoods.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/memory.h"
#include "core/progress.h"
#include "gltf/glb.h"
#include "pipeline/mesh_lods.h"

namespace qf {

PointSet load_point_set(const std::string& path, const ReadOptions& read, const SampleOptions& sample,
                        const std::string& command, ReadReport& report, SampleStats* sampled, TriangleMesh* mesh,
                        std::vector<std::uint32_t>* triangles) {
  progress::step("reading " + path);
  return points_of(read_model(path, read, &report), path, read, sample, command, report, sampled, mesh, triangles);
}

PointSet points_of(Model model, const std::string& path, const ReadOptions& read, const SampleOptions& sample, const std::string& command,
                   ReadReport& report, SampleStats* sampled, TriangleMesh* mesh, std::vector<std::uint32_t>* triangles) {
  if (model.is_mesh) {
    progress::step("sampling the mesh into points (depth peeling)");
    SampleStats stats;
    PointSet points = sample_mesh(model.mesh, sample, path, &stats, triangles);
    if (sampled) *sampled = stats;
    if (mesh) *mesh = std::move(model.mesh);
    return points;
  }
  if (model.points.size() == 0) throw InputError(command + ".empty", path, "", "holds no points");
  if (read.outlier_factor > 0) {
    progress::step("outliers of " + std::to_string(model.points.size()) + " points");
    OutlierOptions outliers;
    outliers.factor = read.outlier_factor;
    report.dropped_outliers += drop_outliers(model.points, outliers);
  }
  return std::move(model.points);
}

namespace {

nlohmann::json level_entry(const BakedLevel& l, const std::string& file) {
  nlohmann::json atlas_sides = nlohmann::json::array();
  for (std::size_t i = 0; i < l.atlas_widths.size(); ++i) atlas_sides.push_back({l.atlas_widths[i], l.atlas_heights[i]});
  return {{"file", file},
          {"level", l.level},
          {"primitives", l.primitives},
          {"texels", l.textures.texels},
          {"quad_texels", l.quad_texels},
          {"texel", canonical_double(static_cast<float>(l.texel))},
          {"atlas_images", l.atlas_images},
          {"atlas_sides", atlas_sides},
          {"bytes", l.glb.size()},
          {"texture_bytes", l.textures.file_bytes},
          {"gpu_bytes", l.textures.gpu_bytes},
          {"error", canonical_double(static_cast<float>(l.error))},
          {"relative_error", canonical_double(static_cast<float>(l.relative_error))},
          {"max_screen_pixels", static_cast<long long>(l.max_screen_pixels)}};
}

nlohmann::json stage_entry(const StageTime& t) {
  return {{"stage", t.stage},
          {"seconds", canonical_double(static_cast<float>(t.seconds))},
          {"resident_mb", canonical_double(static_cast<float>(t.resident_bytes / 1048576.0))},
          {"peak_mb", canonical_double(static_cast<float>(t.peak_bytes / 1048576.0))}};
}

// 3. The impostor levels' files (their .glb bytes moved out of `r`) and the manifest around them.
nlohmann::json impostor_outputs(BakeResult& r, const std::string& stem, const std::string& input_name, std::vector<OutputFile>& files) {
  nlohmann::json levels = nlohmann::json::array();
  for (BakedLevel& l : r.levels) {
    const std::string name = stem + "_L" + std::to_string(l.level) + ".glb";
    levels.push_back(level_entry(l, name));
    files.push_back({name, std::move(l.glb)});
    l.glb.clear();
  }
  nlohmann::json manifest{{"input", input_name},
                          {"points", r.points},
                          {"bounding_box_diagonal", canonical_double(r.diagonal)},
                          {"levels", levels},
                          {"generator", "quasiflat qf-bake"}};
  // Only where it ran: the bake was decomposed on a subsample (pipeline/out_of_core.h).
  if (r.memory.out_of_core)
    manifest["out_of_core"] = {{"subsample_points", r.memory.subsample}, {"scratch_bytes", r.scratch_bytes}};
  return manifest;
}

// 4. Mesh inputs: the sampled points, randomly permuted, as a point impostor (its manifest entry).
nlohmann::json point_impostor_output(const PointSet& points, const AssetOptions& o, float pixel, const std::string& stem,
                                     std::vector<OutputFile>& files) {
  PointImpostorInfo info;
  info.pixel = pixel;
  info.seed = o.point_seed;
  const std::string name = stem + "_points.glb";
  files.push_back({name, encode_point_glb(permuted(points, point_permutation(points.size(), info.seed)), info)});
  return {{"file", name},
          {"points", points.size()},
          {"pixel_size", canonical_double(info.pixel)},
          {"seed", info.seed},
          {"switch_distance", canonical_double(static_cast<float>(point_switch_distance(info)))},
          {"switch_screen_height", info.reference_height},
          {"switch_fov_degrees", canonical_double(info.reference_fov_degrees)}};
}

// 7a. How the bake fitted in memory: the path, the estimate and the limit, and out of core the
// subsample, the scratch file and the batches of quads; the process' peak so far.
nlohmann::json memory_entry(const BakeResult& r) {
  const auto mb = [](double bytes) { return round_to(bytes / 1048576.0, 1); };
  nlohmann::json m{{"path", r.memory.out_of_core ? "out-of-core" : "in-memory"},
                   {"input", r.streamed ? "streamed" : "read whole"},
                   {"estimated_mb", mb(double(r.memory.need))},
                   {"limit_mb", r.memory.limit == SIZE_MAX ? nlohmann::json(nullptr) : nlohmann::json(mb(double(r.memory.limit)))},
                   {"limit_source", r.memory.limit_source},
                   {"peak_mb", mb(double(process_memory("VmHWM:")))}};
  if (r.memory.out_of_core) {
    m["subsample_points"] = r.memory.subsample;
    m["scratch_bytes"] = r.scratch_bytes;
    m["batch_points"] = r.memory.batch_points;
    m["batches"] = r.batches;
  }
  return m;
}

// 7. The report: what was read, the settings, the figures, per-stage time and memory.
nlohmann::json asset_report(AssetBake& a, const AssetOptions& o, const std::string& input_name, const nlohmann::json& levels) {
  BakeResult& r = a.result;
  nlohmann::json stages = nlohmann::json::array();
  for (const StageTime& t : r.times) stages.push_back(stage_entry(t));
  nlohmann::json sampling;  // null for point sets
  if (!a.sampled.backend.empty()) {
    sampling = {{"ldi_size", o.sample.ldi_size},
                {"backend_requested", o.sample.backend},
                {"backend", a.sampled.backend},
                {"per_axis_triangles", o.sample.per_axis_triangles},
                {"pixel", canonical_double(a.sampled.pixel)},
                {"layers", a.sampled.layers},
                {"points_per_axis", a.sampled.points},
                {"degenerate_triangles", a.sampled.degenerate_triangles},
                {"visibility_views", o.sample.visibility.views},
                {"hidden", a.sampled.hidden},
                {"seconds", canonical_double(static_cast<float>(a.sampled.seconds))}};
    if (!a.sampled.fallback.empty()) r.warnings.push_back(a.sampled.fallback);
  }
  return {{"input", input_name},
          {"tool_version", o.tool_version},
          {"gl", a.gl},
          {"format", a.read.format},
          {"points", r.points},
          {"dropped_nonfinite", a.read.dropped_nonfinite},
          {"dropped_outliers", a.read.dropped_outliers},
          {"hierarchy_levels", r.hierarchy_levels},
          {"components", r.components},
          {"cache", r.cache},
          {"memory", memory_entry(r)},
          {"settings",
           {{"outliers", canonical_double(o.read.outlier_factor)},
            {"k", o.bake.analysis.neighborhoods.k},
            {"tau", o.bake.domains.tau},
            {"strict", o.bake.domains.strict},
            {"merge", o.bake.merge},
            {"aim_primitives", !o.bake.amg.target_sizes.empty()},
            {"texel_factor", canonical_double(o.bake.texture.texel_factor)},
            {"texel_density", canonical_double(static_cast<float>(o.bake.texel_density))},
            {"max_texture", o.bake.texture.max_side},
            {"textures", textures_name(o.bake.gltf.textures)},
            {"lod_file", o.lod_file},
            {"mesh_lods", o.mesh_lods == AssetOptions::MeshLods::kSimplify     ? "simplify"
                          : o.mesh_lods == AssetOptions::MeshLods::kClustering ? "clustering"
                                                                               : "none"},
            {"measure", static_cast<bool>(o.measure)},
            {"chain", static_cast<bool>(o.measure) && o.chain}}},
          {"levels", levels},
          {"stages", stages},
          {"sampling", sampling},
          {"warnings", r.warnings}};
}

// 6. The combined LOD file, nearest first: the recommended chain's files, each shown down to its
// min_pixels; without a chain the impostor levels, finest first, each shown down to the size at
// which the next coarser one is accurate enough (the coarsest is never culled).
void lod_file_output(AssetBake& a, const AssetOptions& o, const std::string& stem) {
  std::vector<std::pair<std::string, double>> steps;  // file, shown down to this many pixels
  const bool chain = a.manifest.contains("recommended_chain");
  if (chain) {
    // The asset itself (its nearest entries) is the input file, not one of the bake's.
    for (const nlohmann::json& e : a.manifest["recommended_chain"]["chain"])
      if (e["kind"] != "asset") steps.push_back({e["file"].get<std::string>(), e["min_pixels"].get<double>()});
  } else {
    std::vector<const BakedLevel*> levels;
    for (const BakedLevel& l : a.result.levels) levels.push_back(&l);
    std::sort(levels.begin(), levels.end(), [](const BakedLevel* x, const BakedLevel* y) { return x->level < y->level; });
    for (std::size_t i = 0; i < levels.size(); ++i)
      steps.push_back({stem + "_L" + std::to_string(levels[i]->level) + ".glb", i + 1 < levels.size() ? levels[i + 1]->max_screen_pixels : 0.0});
  }
  if (steps.empty()) {
    a.result.warnings.push_back("no " + stem + "_lods.glb: the recommended chain is the asset itself at every size");
    return;
  }
  // Babylon.js loads every MSFT_lod level at once, coarsest first, and on each level's arrival
  // disposes the next coarser one, loaded or not: a coarser level still decoding its textures when
  // a finer one arrives never finishes, and neither does the load (measured: a torus chain of an
  // impostor level, a mesh LOD and a far impostor level hung Babylon.js 9.31's loader). A level is
  // kept only where its images are no larger than those of every finer level kept (an untextured
  // mesh LOD has none): then each level arrives after the coarser ones. The others stay in the
  // chain as files of their own.
  std::vector<const std::vector<std::uint8_t>*> parts;
  std::vector<double> coverage;
  nlohmann::json names = nlohmann::json::array(), left_out = nlohmann::json::array();
  std::size_t finer_images = std::numeric_limits<std::size_t>::max();
  for (const auto& [file, pixels] : steps) {
    const OutputFile* part = nullptr;
    for (const OutputFile& f : a.files)
      if (f.name == file) part = &f;
    if (!part) throw std::logic_error("lod_file_output: no file " + file);
    const std::size_t images = glb_image_bytes(part->bytes);
    if (images > finer_images) {
      left_out.push_back(file);
      continue;
    }
    finer_images = images;
    parts.push_back(&part->bytes);
    double c = std::min(1.0, pixels / o.lod_screen_height);
    if (!coverage.empty()) c = std::min(c, coverage.back());
    coverage.push_back(canonical_double(static_cast<float>(c)));
    names.push_back(file);
  }
  if (!coverage.empty()) coverage.back() = 0.0;  // the coarsest kept is never culled
  std::vector<std::uint8_t> combined = combine_lod_glb(parts, coverage, chain ? "chain" : "impostor");
  const std::string name = stem + "_lods.glb";
  a.files.push_back({name, std::move(combined)});
  a.manifest["lod_file"] = {{"file", name}, {"screen_height", o.lod_screen_height}, {"parts", names}, {"left_out", left_out}};
}

// 5a. The files to measure (their own figures decide where they hold): the impostor levels; with
// the chain also the mesh LODs and the point impostor, its other candidates.
std::vector<Candidate> measured_candidates(const AssetBake& a, bool chain) {
  std::vector<Candidate> out;
  auto add = [&](const nlohmann::json& entry, const char* kind) {
    const std::string name = entry.at("file").get<std::string>();
    for (const OutputFile& f : a.files)
      if (f.name == name) out.push_back({name, kind, &f.bytes});
  };
  if (chain && a.manifest.contains("mesh_lods"))
    for (const nlohmann::json& l : a.manifest["mesh_lods"]["levels"]) add(l, "mesh_lod");
  for (const nlohmann::json& l : a.manifest.at("levels")) add(l, "impostor_level");
  if (chain && a.manifest.contains("point_impostor")) add(a.manifest["point_impostor"], "point_impostor");
  return out;
}

const FileScores* scores_of(const Measurements& m, const std::string& file) {
  for (const FileScores& f : m.files)
    if (f.file == file) return &f;
  return nullptr;
}

// 5b. Every measured file's max_screen_pixels and holds_from_pixels where it holds by the bar (the
// geometric estimate kept beside it as geometric_max_screen_pixels), with its figures per size, in
// the manifest and in the bake's levels (which the combined LOD file switches by).
void apply_screen_sizes(AssetBake& a, const Measurements& m, const HoldBar& bar) {
  std::vector<nlohmann::json*> entries;
  for (nlohmann::json& l : a.manifest["levels"]) entries.push_back(&l);
  if (a.manifest.contains("mesh_lods") && a.manifest["mesh_lods"].contains("levels"))
    for (nlohmann::json& l : a.manifest["mesh_lods"]["levels"]) entries.push_back(&l);
  if (a.manifest.contains("point_impostor")) entries.push_back(&a.manifest["point_impostor"]);
  for (nlohmann::json* l : entries) {
    const FileScores* f = scores_of(m, l->at("file").get<std::string>());
    if (!f) continue;
    const ScreenWindow w = holding_window(m.sizes, f->at_size, m.asset.at_size, bar);
    nlohmann::json measured = nlohmann::json::array();
    for (std::size_t s = 0; s < m.sizes.size(); ++s) {
      nlohmann::json e = scores_entry(f->at_size[s]);
      e["pixels"] = m.sizes[s];
      e["holds"] = holds(f->at_size[s], m.asset.at_size[s], bar);
      measured.push_back(e);
    }
    if (l->contains("max_screen_pixels")) (*l)["geometric_max_screen_pixels"] = (*l)["max_screen_pixels"];
    (*l)["max_screen_pixels"] = w.max_pixels;
    (*l)["holds_from_pixels"] = w.min_pixels;
    (*l)["measured"] = measured;
    if (l->contains("level"))
      for (BakedLevel& b : a.result.levels)
        if (static_cast<long long>(b.level) == (*l)["level"].get<long long>()) b.max_screen_pixels = w.max_pixels;
  }
}

nlohmann::json measuring_entry(const Measurements& m, const HoldBar& bar) {
  nlohmann::json asset = nlohmann::json::array();
  for (std::size_t s = 0; s < m.sizes.size(); ++s) {
    nlohmann::json e = scores_entry(m.asset.at_size[s]);
    e["pixels"] = m.sizes[s];
    asset.push_back(e);
  }
  return {{"method", "engine"},
          {"sizes", m.sizes},
          {"views", m.views},
          {"truth", m.truth},
          {"hold_rule", "a file holds at a size when, against the truth there, its footprint PSNR is at most psnr_drop below the asset's "
                        "as drawn at that size, its soft IoU at most soft_iou_drop below the asset's, and its coverage at most "
                        "coverage_drop below the asset's (capped at 1) and at least min_coverage; a size where the truth covers under "
                        "half a pixel holds for no file. max_screen_pixels is the largest size measured at which it holds (0: none), "
                        "holds_from_pixels the smallest of the run of sizes from there down at which it holds"},
          {"hold", hold_entry(bar)},
          {"asset", asset}};
}

// The asset's bytes as an engine would load it: the input file and every file it reads (a glTF's
// buffers and images, an OBJ's MTL and textures).
std::size_t asset_bytes(const std::string& path) {
  std::vector<std::string> files{path};
  for (const InputDependency& d : input_dependencies(path)) files.push_back(d.path);
  std::size_t bytes = 0;
  for (const std::string& f : files) {
    std::error_code ec;
    const std::uintmax_t n = std::filesystem::file_size(f, ec);
    if (!ec) bytes += static_cast<std::size_t>(n);
  }
  return bytes;
}

// 1a. What the input is (manifest "source"), so that the saving can be read off beside the
// outputs' bytes: its format, its bytes with every file it reads, and what it holds: a mesh's
// triangles, materials and textures, a point set's points (`points`: as read, before any dropped).
nlohmann::json source_entry(const std::string& path, const ReadReport& read, const Model* model, std::size_t points) {
  nlohmann::json s{{"format", read.format}, {"bytes", asset_bytes(path)}, {"files", 1 + input_dependencies(path).size()}};
  if (model && model->is_mesh) {
    s["triangles"] = model->mesh.triangles.size() + read.dropped_triangles;
    s["materials"] = model->mesh.materials.size();
    s["textures"] = model->mesh.textures.size();
  } else {
    s["points"] = points;
  }
  return s;
}

// What drawing a chain's file costs an engine besides its bytes: triangles (a quad is two), and the
// GPU memory of its textures with their mip levels where the manifest gives it; the input's
// triangles where it is a mesh.
nlohmann::json draw_cost(const nlohmann::json& manifest, const std::string& file) {
  std::vector<const nlohmann::json*> entries;
  for (const nlohmann::json& l : manifest.at("levels")) entries.push_back(&l);
  if (manifest.contains("mesh_lods") && manifest["mesh_lods"].contains("levels"))
    for (const nlohmann::json& l : manifest["mesh_lods"]["levels"]) entries.push_back(&l);
  for (const nlohmann::json* e : entries) {
    if (e->at("file") != file) continue;
    nlohmann::json cost{{"triangles", e->contains("primitives") ? 2 * e->at("primitives").get<std::size_t>() : e->value("triangles", std::size_t{0})}};
    if (e->contains("gpu_bytes")) cost["gpu_bytes"] = (*e)["gpu_bytes"];
    return cost;
  }
  if (manifest.contains("point_impostor") && manifest["point_impostor"].at("file") == file) return {{"points", manifest["point_impostor"]["points"]}};
  if (manifest.contains("input_triangles")) return {{"triangles", manifest["input_triangles"]}};
  return nullptr;
}

void measure_outputs(AssetBake& a, const AssetOptions& o, const std::string& path, const std::string& input_name) {
  Measurements m;
  try {
    m = render::measure_files(path, measured_candidates(a, o.chain), o.chain_rule.bar, *o.measure);
  } catch (const UsageError& e) {
    // No GL driver: the levels are still good files with their geometric sizes (as the sampler
    // falls back to the CPU), without a chain.
    a.result.warnings.push_back(std::string("the outputs were not measured, so the levels keep their geometric max_screen_pixels and there is no "
                                            "recommended chain: ") + e.what());
    return;
  }
  m.asset.file = input_name;
  m.asset.bytes = asset_bytes(path);
  if (!m.gl_renderer.empty()) a.gl = {{"renderer", m.gl_renderer}, {"version", m.gl_version}};
  apply_screen_sizes(a, m, o.chain_rule.bar);
  a.manifest["measuring"] = measuring_entry(m, o.chain_rule.bar);
  if (o.chain) {
    const double diagonal = a.manifest.at("bounding_box_diagonal").get<double>();
    nlohmann::json chain = recommend_chain(m, diagonal, o.chain_rule);
    if (chain.is_null()) return;
    for (nlohmann::json& e : chain["chain"]) e["draw_cost"] = draw_cost(a.manifest, e["file"].get<std::string>());
    a.manifest["recommended_chain"] = chain;
  }
}

// Why an out-of-core bake does not draw its input (empty: it may). The measuring and the page
// draw the whole input as the truth (qf-render's reference scene: a textured quad per point,
// held on the CPU by the GL driver), ~1.1 KB a point (1M-point torus: 1.06 GB peak measuring,
// 1.11 GB for qf-render eval), more than the in-memory bake's ~0.8 KB.
constexpr double kDrawBytesPerPoint = 1100;
std::string drawing_past_limit(const BakeResult& r) {
  const double need = kDrawBytesPerPoint * double(r.points);
  if (!r.memory.out_of_core || need <= double(r.memory.limit)) return "";
  return "drawing the input's " + std::to_string(r.points) + " points as the truth needs about " + format_bytes(need) + ", past the " +
         format_bytes(double(r.memory.limit)) + " of " + r.memory.limit_source;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// 1'. A point set too big to hold whole, whose header gives its count (io/model_io.h
// streamed_point_count): the plan for its count, when it says out of core; nothing otherwise.
std::optional<MemoryPlan> streamed_plan(const std::string& path, const BakeOptions& bake) {
  const std::optional<std::size_t> count = streamed_point_count(path);
  if (!count) return std::nullopt;
  const MemoryPlan plan = plan_bake_memory(*count, bake, false, path);
  return plan.out_of_core ? std::optional<MemoryPlan>(plan) : std::nullopt;
}

// Why a mesh is cheap already (empty: it is not): an opaque mesh of at most `cheap_triangles`
// triangles draws exactly for less than any impostor or LOD of it would cost. Alpha-tested or
// blended cards are never cheap: their own mipmaps thin them far away, where a level keeps them.
std::string cheap_already(const Model& model, std::size_t cheap_triangles) {
  if (!model.is_mesh || model.mesh.triangles.size() > cheap_triangles) return "";
  for (const SurfaceMaterial& m : model.mesh.materials)
    if (m.alpha_mode != AlphaMode::kOpaque) return "";
  return "an opaque mesh of " + std::to_string(model.mesh.triangles.size()) + " triangles (at most --cheap-triangles " +
         std::to_string(cheap_triangles) + ") is cheaper drawn as it is than any impostor or LOD of it: nothing else was written, "
         "and the chain is the asset itself";
}

// 1'. A cheap mesh: no files but the manifest and report, which say why; measured, the asset alone,
// so that its chain (the asset at every size) carries its figures.
void cheap_asset(AssetBake& a, const AssetOptions& o, const std::string& path, const std::string& input_name, const TriangleMesh& mesh,
                 const std::string& why) {
  a.result.points = 0;
  a.result.diagonal = static_cast<float>(mesh.bounds().diagonal());
  a.manifest = impostor_outputs(a.result, std::filesystem::path(input_name).stem().string(), input_name, a.files);
  a.manifest["input_triangles"] = mesh.triangles.size();
  a.manifest["cheap_asset"] = {{"triangles", mesh.triangles.size()}, {"bytes", asset_bytes(path)}, {"reason", why}};
  a.result.warnings.push_back(why);
  if (o.lod_file) a.result.warnings.push_back("no STEM_lods.glb for a cheap mesh: it would hold the asset alone");
  if (o.measure) {
    const auto measure_start = std::chrono::steady_clock::now();
    measure_outputs(a, o, path, input_name);
    a.result.times.push_back({"measure", seconds_since(measure_start), 0, 0});
    if (a.manifest.contains("recommended_chain")) a.manifest["recommended_chain"]["chain"][0]["reason"] = why;
  }
}

}  // namespace

AssetBake bake_asset(const std::string& path, const AssetOptions& o, const std::string& input_name) {
  AssetBake a;
  const std::string stem = std::filesystem::path(input_name).stem().string();
  BakeOptions bake_options = o.bake;
  // 1. Points (a mesh is sampled), unless they stream straight to the out-of-core bake; a cheap
  // mesh is not baked at all.
  const std::optional<MemoryPlan> streamed = streamed_plan(path, bake_options);
  TriangleMesh mesh;
  MeshSurface surface;  // a mesh input's quads draw the mesh itself
  PointSet points;
  nlohmann::json source;  // the input's facts, once read
  if (!streamed) {
    const auto read_start = std::chrono::steady_clock::now();
    progress::step("reading " + path);
    Model model = read_model(path, o.read, &a.read);
    source = source_entry(path, a.read, &model, model.points.size() + a.read.dropped_nonfinite);
    if (const std::string why = cheap_already(model, o.cheap_triangles); !why.empty()) {
      a.result.times.push_back({"read", seconds_since(read_start), 0, 0});
      cheap_asset(a, o, path, input_name, model.mesh, why);
      a.manifest["source"] = source;
      a.report = asset_report(a, o, input_name, a.manifest["levels"]);
      if (o.report_page) a.page = o.report_page(a, path);
      return a;
    }
    points = points_of(std::move(model), path, o.read, o.sample, "bake", a.read, &a.sampled, &mesh, &surface.point_triangles);
  }
  const bool is_mesh = !a.sampled.backend.empty();
  // A mesh's normals: its own; else flat for glTF (as engines draw it), smooth for the others (as
  // the reference is drawn, baker/measure/reference_scene.cpp). Its quads and mesh LODs are drawn so too.
  const bool gltf = a.read.format == "glb" || a.read.format == "gltf";
  if (is_mesh) {
    surface.mesh = &mesh;
    surface.normals = mesh.normals.size() == mesh.positions.size() ? mesh.normals : gltf ? std::vector<Vec3f>{} : mesh.smooth_normals();
  }
  // 2-4. The outputs: mesh LODs, impostor levels, the point impostor. A streamed set's mesh LODs
  // are reconstructed from the subsample it was decomposed on, once baked.
  std::vector<std::string> lod_warnings;
  const auto mesh_lod_outputs_of = [&](const PointSet& reconstructed) {
    progress::step(is_mesh ? "mesh LODs" : "mesh LODs of the reconstructed surface");
    return is_mesh ? mesh_lod_outputs(mesh, o, stem, a.files, !gltf) : reconstructed_lod_outputs(reconstructed, o, stem, a.files, lod_warnings);
  };
  auto lods_start = std::chrono::steady_clock::now();
  nlohmann::json mesh_lods = streamed ? nullptr : mesh_lod_outputs_of(points);
  double lods_seconds = seconds_since(lods_start);
  use_surface_edges(bake_options, is_mesh);
  if (streamed) {
    progress::step("reading " + path + " a block at a time (out of core)");
    bake_options.outlier_factor = o.read.outlier_factor;
    a.result = bake(
        [&](const std::function<void(PointSet&)>& each) { stream_point_set(path, o.read, &a.read, kTilePoints, each); }, *streamed,
        bake_options, path);
    a.read.dropped_outliers = a.result.dropped_outliers;
    lods_start = std::chrono::steady_clock::now();
    mesh_lods = mesh_lod_outputs_of(a.result.subsample);
    a.result.subsample = PointSet();
    lods_seconds = seconds_since(lods_start);
  } else {
    // A point set is handed over: an out-of-core bake frees it once on disk (a mesh's points stay,
    // for its point impostor; a mesh is never baked out of core).
    a.result = is_mesh ? bake(points, bake_options, path, &surface) : bake(std::move(points), bake_options, path);
  }
  // Outliers past 1% may be a clean set's sparse parts (a terrestrial scan's far points).
  if (a.read.dropped_outliers * 100 > a.result.points + a.read.dropped_outliers) {
    char factor[32];
    std::snprintf(factor, sizeof factor, "%g", double(o.read.outlier_factor));
    a.result.warnings.push_back(std::to_string(a.read.dropped_outliers) + " points (more than 1%) were dropped as outliers, farther than " + factor +
                      " x the median spacing from their neighbours; if they are sparse parts of the surface, give a larger --outliers, or 0 "
                      "to keep every point");
  }
  if (!is_mesh && !o.mesh_only_given.empty()) {
    std::string names;
    for (const std::string& n : o.mesh_only_given) names += (names.empty() ? "" : ", ") + n;
    a.result.warnings.push_back(names + (o.mesh_only_given.size() > 1 ? " apply" : " applies") +
                                " to mesh inputs only; this input is a point set: ignored");
  }
  a.manifest = impostor_outputs(a.result, stem, input_name, a.files);
  // A streamed set was never whole in memory: its points are those baked and those dropped.
  a.manifest["source"] = streamed ? source_entry(path, a.read, nullptr, a.result.points + a.read.dropped_nonfinite + a.read.dropped_outliers)
                                  : source;
  if (is_mesh) a.manifest["input_triangles"] = mesh.triangles.size();
  if (is_mesh && o.point_impostor) {
    progress::step("point impostor");
    a.manifest["point_impostor"] = point_impostor_output(points, o, a.sampled.pixel, stem, a.files);
  }
  a.result.warnings.insert(a.result.warnings.end(), lod_warnings.begin(), lod_warnings.end());
  if (!mesh_lods.is_null()) {
    a.manifest["mesh_lods"] = std::move(mesh_lods);
    a.result.times.push_back({"mesh lods", lods_seconds, 0, 0});
  }
  // 5. Every output measured on screen: honest screen sizes, the recommended chain. Not where an
  //    out-of-core bake's limit cannot hold the input drawn as the truth.
  const std::string undrawn = drawing_past_limit(a.result);
  if (o.measure && !undrawn.empty())
    a.result.warnings.push_back("the outputs were not measured (" + undrawn + "), so the levels keep their geometric max_screen_pixels "
                                "and there is no recommended chain; give --no-measure to say so, or more --max-memory");
  if (o.report_page && !undrawn.empty())
    a.result.warnings.push_back("no report.html (" + undrawn + "); give --no-report-html to say so, or more --max-memory");
  if (o.measure && undrawn.empty()) {
    const auto measure_start = std::chrono::steady_clock::now();
    measure_outputs(a, o, path, input_name);
    a.result.times.push_back({"measure", seconds_since(measure_start), 0, 0});
  }
  // Where the mesh LODs stop above their budgets, said once the LODs are measured (with its figures).
  if (const std::string stalled = stalled_lods_warning(a.manifest); !stalled.empty()) a.result.warnings.push_back(stalled);
  // 6. All of them in one file.
  if (o.lod_file) {
    const auto lod_start = std::chrono::steady_clock::now();
    progress::step("the LOD file");
    lod_file_output(a, o, stem);
    a.result.times.push_back({"lod file", seconds_since(lod_start), 0, 0});
  }
  // 7. The report, then the page, which shows it (its time is in the report's stages, as the
  // page's own: "report page").
  a.report = asset_report(a, o, input_name, a.manifest["levels"]);
  if (o.report_page && undrawn.empty()) {
    const auto page_start = std::chrono::steady_clock::now();
    progress::step("report page");
    a.page = o.report_page(a, path);
    a.result.times.push_back({"report page", seconds_since(page_start), 0, 0});
    a.report["stages"].push_back(stage_entry(a.result.times.back()));
  }
  return a;
}

nlohmann::json read_asset_manifest(const std::string& folder) {
  std::ifstream in(folder + "/manifest.json");
  if (!in) return nullptr;
  nlohmann::json m = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  return m.is_object() ? m : nullptr;
}

namespace {

// The well-formed entries of a manifest's "files" list; false when the list is missing or broken.
bool each_listed(const nlohmann::json& m, const std::function<void(const std::string&, std::uintmax_t)>& visit) {
  if (!m.is_object() || !m.contains("files") || !m["files"].is_array()) return false;
  for (const nlohmann::json& f : m["files"]) {
    if (!f.is_object() || !f.contains("name") || !f["name"].is_string() || !f.contains("bytes") || !f["bytes"].is_number_unsigned())
      return false;
    visit(f["name"].get<std::string>(), f["bytes"].get<std::uintmax_t>());
  }
  return true;
}

}  // namespace

std::vector<std::string> listed_files(const nlohmann::json& manifest) {
  std::vector<std::string> out;
  each_listed(manifest, [&](const std::string& name, std::uintmax_t) { out.push_back(name); });
  return out;
}

bool listed_files_present(const std::string& folder, const nlohmann::json& manifest) {
  bool all = true;
  const bool listed = each_listed(manifest, [&](const std::string& name, std::uintmax_t bytes) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(folder + "/" + name, ec);
    all = all && !ec && size == bytes;
  });
  return listed && all;
}

namespace {

// output_bytes of the files `listed` (name: bytes).
OutputBytes output_bytes_of(const nlohmann::json& manifest, const std::map<std::string, std::uintmax_t>& listed) {
  OutputBytes out;
  for (const auto& [name, bytes] : listed) out.written += bytes;
  if (!manifest.is_object() || !manifest.contains("recommended_chain")) return out;
  std::set<std::string> shipped;
  for (const nlohmann::json& e : manifest["recommended_chain"].value("chain", nlohmann::json::array()))
    if (e.value("kind", std::string()) != "asset" && e.contains("file")) shipped.insert(e["file"].get<std::string>());
  out.chain = 0;
  for (const std::string& f : shipped)
    if (listed.count(f)) *out.chain += listed.at(f);
  return out;
}

}  // namespace

OutputBytes output_bytes(const nlohmann::json& manifest) {
  std::map<std::string, std::uintmax_t> listed;
  each_listed(manifest, [&](const std::string& name, std::uintmax_t bytes) { listed[name] = bytes; });
  return output_bytes_of(manifest, listed);
}

OutputBytes output_bytes(const nlohmann::json& manifest, const std::vector<OutputFile>& files) {
  std::map<std::string, std::uintmax_t> listed;
  for (const OutputFile& f : files) listed[f.name] = f.bytes.size();
  return output_bytes_of(manifest, listed);
}

void write_asset(OutputFolder& out, const std::vector<OutputFile>& files, nlohmann::json manifest, const nlohmann::json& report,
                 const std::string& page) {
  // What the folder's last bake wrote: replaced, never carried over (a rebake with other levels
  // leaves no stale level, one without a page no old page). Anything else there is carried.
  const std::vector<std::string> before = listed_files(read_asset_manifest(out.path()));
  nlohmann::json listed = nlohmann::json::array();
  for (const OutputFile& f : files) listed.push_back({{"name", f.name}, {"bytes", f.bytes.size()}});
  manifest["files"] = listed;
  out.replace(
      [&](const std::string& staging) {
        for (const OutputFile& f : files) write_bytes_atomically(staging + "/" + f.name, f.bytes);
        if (!report.is_null())
          write_file_atomically(staging + "/report.json", [&](std::ostream& o) { o << report.dump(2) << "\n"; });
        if (!page.empty()) write_file_atomically(staging + "/report.html", [&](std::ostream& o) { o << page; });
        write_file_atomically(staging + "/manifest.json", [&](std::ostream& o) { o << manifest.dump(2) << "\n"; });
      },
      [&](const std::string& name) {
        if (name == "manifest.json" || name == "report.json" || name == "report.html") return false;
        return std::find(before.begin(), before.end(), name) == before.end();
      });
}

}  // namespace qf
