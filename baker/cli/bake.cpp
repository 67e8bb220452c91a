// The bake command (the main job): a point set or mesh in, one .glb per chosen level (and the mesh
// outputs), a manifest and a report out (pipeline/asset). Everything is written into a temporary
// folder inside OUTDIR and moved into place, the manifest last, so a failed or killed bake leaves
// no half-written file.
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <ostream>

#include "cli/commands.h"
#include "core/error.h"
#include "core/file_io.h"
#include "pipeline/asset.h"
#include "tools/measure.h"

namespace qf::cli {

CommandSpec bake_spec() {
  CommandSpec spec{"bake", "IN -o OUTDIR [options]   (also: qf-bake IN -o OUTDIR)",
                   "bake a point set into impostor levels: one .glb per level, manifest.json, report.json",
                   "Each level's .glb holds the domain primitives as textured quads (colour + basis function\n"
                   "as alpha, normal maps when the input has normals) in one atlas, and the QF_impostor_level\n"
                   "extension (schemas/QF_impostor_level). manifest.json lists the levels; report.json the\n"
                   "settings, times and counts. Nothing is left half-written if the bake fails.",
                   {output_option("OUTDIR", "output folder (created if needed); required"),
                    {"primitives", 'n', "N,N,...", "1000,300,100,30", "bake the levels nearest these numbers of primitives"},
                    {"levels", 0, "K,K,...", "", "instead: these level numbers (0 = points, negative = from the coarsest)"},
                    {"tau", 0, "T", "0.05", "domain threshold"},
                    {"strict", 0, "", "", "strict domains: each point only in its strongest function's domain (thesis 2.5):\n"
                                          "alpha 1 on its own points' splats, no overlap between quads"},
                    {"texel-density", 0, "D", "1", "texels per screen pixel where a level is drawn largest (its max_screen_pixels):\n"
                                                  "coarse levels get coarse textures, never finer than --texel; 0 = from --texel alone"},
                    {"texel", 0, "F", "1", "texels no smaller than F x the domain's mean point radius; given alone, it sets the\n"
                                           "texel size at every level (as --texel-density 0)"},
                    {"max-texture", 0, "N", "1024", "largest texture side of one primitive, texels"},
                    {"margin", 0, "M", "0", "extra rectangle margin, in mean point radii"},
                    {"lod-file", 0, "", "", "also write STEM_lods.glb: every level in one file under MSFT_lod (finest in the scene,\n"
                                             "the others as its lower LODs, switched by MSFT_screencoverage)"},
                    {"lod-screen-height", 0, "PX", "1080", "screen height the MSFT_screencoverage values and the chain's switch distances assume"},
                    {"point-seed", 0, "S", "1", "mesh inputs: seed of the point impostor's random order (STEM_points.glb)"},
                    {"no-points", 0, "", "", "mesh inputs: do not write the point impostor"},
                    {"mesh-lods", 0, "simplify|clustering|none", "simplify",
                     "mesh inputs: the mesh LODs beside the impostors: simplify = meshoptimizer's edge collapse\n"
                     "(STEM_S<i>.glb at the input's triangles / 4, 16, 64, 256, 1024), clustering = seed 002's\n"
                     "vertex clustering with thick edges (STEM_C<i>.glb, cells = diagonal / 128 .. 8)"},
                    {"no-mesh-lods", 0, "", "", "the same as --mesh-lods none"},
                    {"no-measure", 0, "", "", "do not measure the outputs on screen: each level keeps its geometric max_screen_pixels\n"
                                              "(error under half a pixel) and there is no chain (needs no GL driver)"},
                    {"measure-views", 0, "N", "4", "directions each output is drawn from when measured, at 128, 64, 32 and 16 px on\n"
                                                   "screen (and 256 with --chain), by the engine method against the truth (the input drawn\n"
                                                   "once at 4x the largest size, box-filtered to each): a level's max_screen_pixels is the largest of those sizes at which its\n"
                                                   "look holds (PSNR within 1 dB of its best, IoU within 0.05 of its IoU there; manifest measuring)"},
                    {"chain", 0, "", "", "also the recommended chain (manifest recommended_chain): the mesh LODs and the point\n"
                                         "impostor are measured too; per band, never more bytes than nearer, the smallest file\n"
                                         "that reaches --chain-psnr and IoU 0.9 (else the best PSNR less 1 dB per doubling of\n"
                                         "bytes), with its switch distance (--lod-screen-height, 60 degree field of view); with\n"
                                         "--lod-file, STEM_lods.glb holds the chain's files"},
                    {"chain-psnr", 0, "DB", "30", "--chain: the quality bar, dB (engine method against the truth; implies --chain)"},
                    drop_nonfinite_option(), quiet_option()},
                   1, 1};
  append_point_input_options(spec.options);
  return spec;
}

AssetOptions read_asset_options(const OptionValues& args) {
  AssetOptions a;
  BakeOptions& o = a.bake;
  o.analysis = read_analysis_options(args);
  o.domains.tau = args.get_double("tau", o.domains.tau, 0.0, 1.0);
  o.domains.strict = args.flag("strict");
  o.merge = args.flag("merge");
  o.merge_options = read_merge_options(args, o.domains);
  o.texture.texel_factor = static_cast<float>(args.get_double("texel", o.texture.texel_factor, 0.01, 100.0));
  // An explicit --texel is an override: the same texel size at every level, unless a density is
  // asked for too.
  o.texel_density = args.get_double("texel-density", args.has("texel") ? 0.0 : o.texel_density, 0.0, 1000.0);
  o.texture.max_side = static_cast<int>(args.get_int("max-texture", o.texture.max_side, 4, 4096 - 8));
  o.support.margin = static_cast<float>(args.get_double("margin", o.support.margin, 0.0, 100.0));
  if (args.has("levels") && args.has("primitives")) throw UsageError("give --levels or --primitives, not both");
  if (args.has("levels")) {
    o.levels = args.get_int_list("levels", std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
  } else if (args.has("primitives")) {
    o.primitives.clear();
    for (long long n : args.get_int_list("primitives", 1, std::numeric_limits<long long>::max()))
      o.primitives.push_back(static_cast<std::size_t>(n));
  }
  o.cache_dir = read_cache_dir(args);
  a.lod_file = args.flag("lod-file");
  a.lod_screen_height = args.get_double("lod-screen-height", a.lod_screen_height, 1.0, 100000.0);
  a.read.drop_nonfinite = args.flag("drop-nonfinite");
  a.sample = read_sample_options(args);
  a.point_seed = static_cast<std::uint64_t>(args.get_int("point-seed", 1, 0, 1ll << 62));
  a.point_impostor = !args.flag("no-points");
  const std::string lods = args.flag("no-mesh-lods") ? "none" : args.get_choice("mesh-lods", {"simplify", "clustering", "none"}, "simplify");
  a.mesh_lods = lods == "simplify" ? AssetOptions::MeshLods::kSimplify
                : lods == "clustering" ? AssetOptions::MeshLods::kClustering
                                       : AssetOptions::MeshLods::kNone;
  render::MeasureOptions measure;
  measure.views = static_cast<int>(args.get_int("measure-views", measure.views, 1, 1000));
  measure.read = a.read;
  a.chain = args.flag("chain") || args.has("chain-psnr");
  // The chain adds a near band and the input as drawn (the floor an impostor must beat).
  if (a.chain) measure.sizes.insert(measure.sizes.begin(), 256), measure.as_drawn = true;
  a.chain_rule.min_psnr = args.get_double("chain-psnr", a.chain_rule.min_psnr, 0.0, 99.0);
  a.chain_rule.screen_height = a.lod_screen_height;
  if (args.flag("no-measure") && (a.chain || args.has("measure-views")))
    throw UsageError("--no-measure leaves nothing for --chain, --chain-psnr or --measure-views to do");
  if (!args.flag("no-measure"))
    a.measure = [measure](const std::string& input, const std::vector<Candidate>& candidates) {
      return render::measure_files(input, candidates, measure);
    };
  return a;
}

void print_bake_summary(const AssetBake& a, const std::string& in, const std::string& outdir) {
  const BakeResult& r = a.result;
  std::fprintf(stderr, "qf-bake: %s (%zu points) -> %s, hierarchy of %zu levels (cache: %s)\n", in.c_str(), r.points,
               outdir.c_str(), r.hierarchy_levels, r.cache.c_str());
  for (const BakedLevel& l : r.levels)
    std::fprintf(stderr, "  level %zu: %zu primitives, %zu texels, error %.3g (%.2g of the diagonal)\n", l.level, l.primitives,
                 l.texels, l.error, l.relative_error);
  double total = 0;
  for (const StageTime& t : r.times) total += t.seconds;
  std::fprintf(stderr, "  time: %.3f s, %zu files\n", total + a.sampled.seconds, a.files.size() + 2);
  if (!a.sampled.backend.empty())
    std::fprintf(stderr, "  sampled: %s, pixel %.4g, layers %d/%d/%d, %.3f s\n", a.sampled.backend.c_str(), a.sampled.pixel,
                 a.sampled.layers[0], a.sampled.layers[1], a.sampled.layers[2], a.sampled.seconds);
  for (const std::string& w : r.warnings) std::fprintf(stderr, "  warning: %s\n", w.c_str());
}

int run_bake(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  const std::string outdir = args.require("output");
  const AssetOptions options = read_asset_options(args);
  const AssetBake a = bake_asset(in, options, in);
  write_asset(outdir, a.files, a.manifest, a.report);
  if (!args.flag("quiet")) print_bake_summary(a, in, outdir);
  return 0;
}

}  // namespace qf::cli
