// The bake command (the main job): a point set in, one .glb per chosen level, a manifest and a
// report out. Everything is written into a temporary folder inside OUTDIR and moved into place
// at the end, the manifest last, so a failed or killed bake leaves no half-written file.
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ostream>

#include "cli/commands.h"
#include "core/error.h"
#include "core/file_io.h"
#include "pipeline/bake.h"

namespace qf::cli {

CommandSpec bake_spec() {
  CommandSpec spec{"bake", "IN -o OUTDIR [options]   (also: qf-bake IN -o OUTDIR)",
                   "bake a point set into impostor levels: one .glb per level, manifest.json, report.json",
                   "Each level's .glb holds the domain primitives as textured quads (colour + basis function\n"
                   "as alpha, normal maps when the input has normals) in one atlas, and the QF_impostor_level\n"
                   "extension (schemas/QF_impostor_level). manifest.json lists the levels; report.json the\n"
                   "settings, times and counts. Nothing is left half-written if the bake fails.",
                   {{"output", 'o', "OUTDIR", "", "output folder (created if needed); required"},
                    {"primitives", 'n', "N,N,...", "1000,300,100,30", "bake the levels nearest these numbers of primitives"},
                    {"levels", 0, "K,K,...", "", "instead: these level numbers (0 = points, negative = from the coarsest)"},
                    {"tau", 0, "T", "0.05", "domain threshold"},
                    {"texel", 0, "F", "1", "texel size = F x the domain's mean point radius"},
                    {"max-texture", 0, "N", "1024", "largest texture side of one primitive, texels"},
                    {"margin", 0, "M", "0", "extra rectangle margin, in mean point radii"},
                    {"lod-file", 0, "", "", "also write STEM_lods.glb: every level in one file under MSFT_lod (finest in the scene,\n"
                                             "the others as its lower LODs, switched by MSFT_screencoverage)"},
                    {"lod-screen-height", 0, "PX", "1080", "screen height the MSFT_screencoverage values assume"},
                    {"point-seed", 0, "S", "1", "mesh inputs: seed of the point impostor's random order (STEM_points.glb)"},
                    {"no-points", 0, "", "", "mesh inputs: do not write the point impostor"},
                    {"no-mesh-lods", 0, "", "", "mesh inputs: do not write the vertex-clustering LODs (STEM_C<i>.glb, cells = diagonal/128../8)"},
                    drop_nonfinite_option(),
                    {"quiet", 'q', "", "", "print nothing on success"}},
                   1, 1};
  for (const auto& group : {merge_option_specs(), cache_option_specs(), analysis_option_specs(), sample_option_specs()})
    spec.options.insert(spec.options.end(), group.begin(), group.end());
  return spec;
}

int run_bake(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  if (!args.has("output")) throw UsageError("bake needs -o OUTDIR (see qf-bake bake --help)");
  const std::string outdir = args.get("output");
  BakeOptions o;
  o.analysis = read_analysis_options(args);
  o.domains.tau = args.get_double("tau", o.domains.tau, 0.0, 1.0);
  o.merge = args.flag("merge");
  o.merge_options = read_merge_options(args, o.domains);
  o.texture.texel_factor = static_cast<float>(args.get_double("texel", o.texture.texel_factor, 0.01, 100.0));
  o.texture.max_side = static_cast<int>(args.get_int("max-texture", o.texture.max_side, 4, 4096 - 8));
  o.support.margin = static_cast<float>(args.get_double("margin", o.support.margin, 0.0, 100.0));
  if (args.has("levels") && args.has("primitives")) throw UsageError("give --levels or --primitives, not both");
  if (args.has("levels")) {
    for (const std::string& t : split_list(args.get("levels"))) {
      try {
        o.levels.push_back(std::stoll(t));
      } catch (const std::exception&) {
        throw UsageError("--levels expects integers separated by commas, got '" + t + "'");
      }
    }
  } else if (args.has("primitives")) {
    o.primitives.clear();
    for (const std::string& t : split_list(args.get("primitives"))) {
      char* end = nullptr;
      const unsigned long long v = std::strtoull(t.c_str(), &end, 10);
      if (!end || *end || v == 0) throw UsageError("--primitives expects positive integers separated by commas, got '" + t + "'");
      o.primitives.push_back(static_cast<std::size_t>(v));
    }
  }
  o.cache_dir = read_cache_dir(args);
  o.lod_file = args.flag("lod-file");
  o.lod_screen_height = args.get_double("lod-screen-height", o.lod_screen_height, 1.0, 100000.0);

  ReadReport read_report;
  SampleStats sampled;
  TriangleMesh mesh;
  const PointSet points = load_points(in, args, "bake", read_report, &sampled, &mesh);
  // Mesh inputs: vertex-clustering LODs for near and middle distances beside the impostors.
  std::vector<LodMesh> mesh_lods;
  if (!sampled.backend.empty() && !args.flag("no-mesh-lods")) {
    const VertexGrading grading = grade_vertices(mesh);
    ClusterOptions co;
    for (double c : default_cluster_cells(mesh)) {
      co.cell = static_cast<float>(c);
      mesh_lods.push_back(cluster_mesh(mesh, grading, co));
    }
  }
  BakeResult r;
  try {
    r = bake(points, o, in);
  } catch (const std::out_of_range& e) {
    throw UsageError(std::string("--levels: ") + e.what());
  }

  // Write into a private folder inside OUTDIR, then move the files into place, manifest last.
  write_folder_atomically(outdir, "qf-bake", [&](const std::string& staging, std::vector<std::string>& files) {
    const std::string stem = std::filesystem::path(in).stem().string();
    nlohmann::json levels = nlohmann::json::array();
    for (const BakedLevel& l : r.levels) {
      const std::string name = stem + "_L" + std::to_string(l.level) + ".glb";
      write_bytes_atomically(staging + "/" + name, l.glb);
      files.push_back(name);
      levels.push_back({{"file", name},
                        {"level", l.level},
                        {"primitives", l.primitives},
                        {"texels", l.texels},
                        {"atlas_images", l.atlas_images},
                        {"error", canonical_double(static_cast<float>(l.error))},
                        {"relative_error", canonical_double(static_cast<float>(l.relative_error))},
                        {"max_screen_pixels", static_cast<long long>(l.max_screen_pixels)}});
    }
    std::string lod_name;
    if (!r.lod_glb.empty()) {
      lod_name = stem + "_lods.glb";
      write_bytes_atomically(staging + "/" + lod_name, r.lod_glb);
      files.push_back(lod_name);
    }
    // Mesh inputs: the sampled points, randomly permuted, as a point impostor.
    nlohmann::json point_entry;
    if (!sampled.backend.empty() && !args.flag("no-points")) {
      PointImpostorInfo info;
      info.pixel = sampled.pixel;
      info.seed = static_cast<std::uint64_t>(args.get_int("point-seed", 1, 0, 1ll << 62));
      const std::string name = stem + "_points.glb";
      write_bytes_atomically(staging + "/" + name, encode_point_glb(permuted(points, point_permutation(points.size(), info.seed)), info));
      files.push_back(name);
      point_entry = {{"file", name},
                     {"points", points.size()},
                     {"pixel_size", canonical_double(info.pixel)},
                     {"seed", info.seed},
                     {"switch_distance", canonical_double(static_cast<float>(point_switch_distance(info)))},
                     {"switch_screen_height", info.reference_height},
                     {"switch_fov_degrees", canonical_double(info.reference_fov_degrees)}};
    }
    nlohmann::json mesh_levels;
    if (!mesh_lods.empty()) mesh_levels = write_cluster_levels(mesh_lods, staging, stem, files);
    nlohmann::json manifest{{"input", in},
                            {"points", r.points},
                            {"bounding_box_diagonal", canonical_double(r.diagonal)},
                            {"levels", levels},
                            {"generator", "quasiflat qf-bake"}};
    if (!point_entry.is_null()) manifest["point_impostor"] = point_entry;
    if (!mesh_levels.is_null())
      manifest["mesh_lods"] = {{"levels", mesh_levels},
                               {"lod_rule", "largest cell_width <= X * R, R = 2 D tan(fov/2) / window height, X = 5; "
                                            "thick line width = _THICKNESS / R pixels"}};
    if (!lod_name.empty()) manifest["lod_file"] = {{"file", lod_name}, {"screen_height", o.lod_screen_height}};
    nlohmann::json stages = nlohmann::json::array();
    for (const StageTime& t : r.times) stages.push_back({{"stage", t.stage},
                                                                    {"seconds", canonical_double(static_cast<float>(t.seconds))},
                                                                    {"resident_mb", canonical_double(static_cast<float>(t.resident_bytes / 1048576.0))},
                                                                    {"peak_mb", canonical_double(static_cast<float>(t.peak_bytes / 1048576.0))}});
    // Mesh inputs: how they were sampled (null for point sets).
    nlohmann::json sampling;
    if (!sampled.backend.empty()) {
      const SampleOptions so = read_sample_options(args);
      sampling = {{"ldi_size", so.ldi_size},
                  {"backend_requested", so.backend},
                  {"backend", sampled.backend},
                  {"per_axis_triangles", so.per_axis_triangles},
                  {"pixel", canonical_double(sampled.pixel)},
                  {"layers", sampled.layers},
                  {"points_per_axis", sampled.points},
                  {"degenerate_triangles", sampled.degenerate_triangles},
                  {"seconds", canonical_double(static_cast<float>(sampled.seconds))}};
      if (!sampled.fallback.empty()) r.warnings.push_back(sampled.fallback);
    }
    nlohmann::json report{{"input", in},
                          {"format", read_report.format},
                          {"points", r.points},
                          {"dropped_nonfinite", read_report.dropped_nonfinite},
                          {"hierarchy_levels", r.hierarchy_levels},
                          {"components", r.components},
                          {"cache", r.cache},
                          {"settings",
                           {{"k", o.analysis.neighborhoods.k},
                            {"tau", o.domains.tau},
                            {"merge", o.merge},
                            {"texel_factor", canonical_double(o.texture.texel_factor)},
                            {"max_texture", o.texture.max_side},
                            {"lod_file", o.lod_file}}},
                          {"levels", levels},
                          {"stages", stages},
                          {"sampling", sampling},
                          {"warnings", r.warnings}};
    write_file_atomically(staging + "/report.json", [&](std::ostream& out) { out << report.dump(2) << "\n"; });
    write_file_atomically(staging + "/manifest.json", [&](std::ostream& out) { out << manifest.dump(2) << "\n"; });
    files.push_back("report.json");
    files.push_back("manifest.json");
  });
  if (!args.flag("quiet")) {
    std::fprintf(stderr, "qf-bake: %s (%zu points) -> %s, hierarchy of %zu levels (cache: %s)\n", in.c_str(), r.points,
                 outdir.c_str(), r.hierarchy_levels, r.cache.c_str());
    for (const BakedLevel& l : r.levels)
      std::fprintf(stderr, "  level %zu: %zu primitives, %zu texels, error %.3g (%.2g of the diagonal), %zu bytes\n", l.level,
                   l.primitives, l.texels, l.error, l.relative_error, l.glb.size());
    double total = 0;
    for (const StageTime& t : r.times) total += t.seconds;
    std::fprintf(stderr, "  time: %.3f s\n", total);
    if (!sampled.backend.empty())
      std::fprintf(stderr, "  sampled: LDI %d (%s), pixel %.4g, layers %d/%d/%d, %.3f s\n", read_sample_options(args).ldi_size,
                   sampled.backend.c_str(), sampled.pixel, sampled.layers[0], sampled.layers[1], sampled.layers[2], sampled.seconds);
    for (const std::string& w : r.warnings) std::fprintf(stderr, "  warning: %s\n", w.c_str());
  }
  return 0;
}

}  // namespace qf::cli
