// The bake command (the main job): a point set or mesh in, one .glb per chosen level (and the mesh
// outputs), a manifest and a report out (pipeline/asset). OUTDIR is built beside itself and swapped
// in whole under a lock (core/output_folder.h), so a failed or killed bake leaves the old bake or
// the new one, and a second bake into OUTDIR is refused while one runs.
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <ostream>

#include "cli/commands.h"
#include "cli/program.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/output_folder.h"
#include "core/memory.h"
#include "core/progress.h"
#include "pipeline/asset.h"
#include "measure/measure.h"
#include "tools/report_html.h"

namespace qf::cli {

CommandSpec bake_spec() {
  CommandSpec spec{"bake", "IN -o OUTDIR [options]   (also: qf-bake IN -o OUTDIR)",
                   "bake a point set into impostor levels: one .glb per level, manifest.json, report.json, report.html",
                   "Each level's .glb holds the domain primitives as textured quads (colour + basis function\n"
                   "as alpha, normal maps when the input has normals) in one atlas, and the QF_impostor_level\n"
                   "extension (schemas/QF_impostor_level). manifest.json lists the levels; report.json the\n"
                   "settings, times and counts; report.html shows it all in a browser (see --no-report-html).\n"
                   "OUTDIR is replaced whole (built beside it, then swapped in): a failed or killed bake\n"
                   "leaves the old bake or the new one, never a mix; files of your own in it are kept. A\n"
                   "second bake into OUTDIR while one runs is refused (exit 5). A glTF input may come\n"
                   "compressed from glTF-Transform or gltfpack (meshopt, quantized, Draco, KTX2 or WebP\n"
                   "textures): it is decoded; one requiring any other extension is refused (exit 1).",
                   {output_option("OUTDIR", "output folder (created if needed); required"),
                    {"primitives", 'n', "N,N,...", "1000,300,100,30", "bake the levels nearest these numbers of primitives"},
                    {"levels", 0, "K,K,...", "", "instead: these level numbers (0 = points, negative = from the coarsest)"},
                    {"aim-primitives", 0, "", "", "coarsen the AMG hierarchy so that levels land on the --primitives counts (within\n"
                                                  "~1%) instead of the nearest level of its own (a factor 2-3 apart): an out-of-core bake\n"
                                                  "and the in-memory one then get the same numbers of quads"},
                    {"tau", 0, "T", "0.05", "domain threshold"},
                    {"strict", 0, "", "", "strict domains: each point only in its strongest function's domain (thesis 2.5):\n"
                                          "alpha 1 on its own points' splats, no overlap between quads"},
                    {"texel-density", 0, "D", "1", "texels per screen pixel where a level is drawn largest (its max_screen_pixels):\n"
                                                  "coarse levels get coarse textures, never finer than --texel; 0 = from --texel alone"},
                    {"texel", 0, "F", "1", "texels no smaller than F x the domain's mean point radius; given alone, it sets the\n"
                                           "texel size at every level (as --texel-density 0)"},
                    {"max-texture", 0, "N", "1024", "largest texture side of one primitive, texels"},
                    {"margin", 0, "M", "0", "extra rectangle margin, in mean point radii"},
                    {"textures", 0, "png|ktx2|webp", "png", "the levels' textures: png (every engine loads them; the engine makes the mip levels,\n"
                                                          "by box filtering), ktx2 (Basis Universal, KHR_texture_basisu, required: ~1/4 of the\n"
                                                          "GPU memory, coverage-preserving mip levels in the file; three.js needs its KTX2Loader)\n"
                                                          "or webp (EXT_texture_webp, required: fewer file bytes, the GPU memory and mip levels\n"
                                                          "of png; three.js and Babylon.js load it, Blender 3.4 does not). ktx2 also makes a\n"
                                                          "textured mesh LOD's textures KTX2; with webp they stay png"},
                    {"ktx2-color", 0, "etc1s|uastc", "etc1s", "--textures ktx2: the Basis codec of colour (+ alpha) and emission textures"},
                    {"ktx2-normal", 0, "etc1s|uastc", "uastc", "--textures ktx2: the Basis codec of normal maps and occlusion/roughness/metallic"},
                    {"ktx2-quality", 0, "Q", "128", "--textures ktx2: ETC1S quality, 1..255 (codebook sizes; more is larger and sharper)"},
                    {"webp-color", 0, "Q|lossless", "lossless", "--textures webp: colour (+ alpha, always exact) and emission: lossless, or lossy at quality Q\n"
                                                              "(1..100; 80: smaller for textured meshes' colour)"},
                    {"webp-normal", 0, "Q|lossless", "lossless", "--textures webp: normal maps: lossless, or lossy at quality Q (1..100; 90: 18% smaller, up to 0.36 dB worse)"},
                    {"lod-file", 0, "", "", "also write STEM_lods.glb: every level in one file under MSFT_lod (finest in the scene,\n"
                                             "the others as its lower LODs, switched by MSFT_screencoverage)"},
                    {"lod-screen-height", 0, "PX", "1080", "screen height the MSFT_screencoverage values and the chain's switch distances assume"},
                    {"cheap-triangles", 0, "N", "256", "an opaque mesh of at most N triangles is cheap already: it is measured, not baked (only\n"
                                                       "manifest.json and the reports, which say why; the chain is the asset itself); 0 bakes\n"
                                                       "every mesh. Meshes with alpha-tested or blended materials are always baked"},
                    {"points", 0, "", "", "mesh inputs: also write the point impostor (STEM_points.glb), the sampled points; off\n"
                                          "by default, as the points outweigh most meshes they come from"},
                    {"point-seed", 0, "S", "1", "mesh inputs, with --points: seed of the point impostor's random order"},
                    {"mesh-lods", 0, "simplify|clustering|none", "simplify",
                     "the mesh LODs beside the impostors: simplify = meshoptimizer's edge collapse\n"
                     "(STEM_S<i>.glb at the mesh's triangles / 4, 16, 64, 256, 1024; a point set's mesh is its\n"
                     "surface reconstructed by CGAL's advancing front from up to 50k of its points), clustering =\n"
                     "seed 002's vertex clustering with thick edges (mesh inputs: STEM_C<i>.glb, cells = diagonal\n"
                     "/ 128 .. 8; a point set gets none)"},
                    {"no-mesh-lods", 0, "", "", "the same as --mesh-lods none"},
                    {"no-measure", 0, "", "", "do not measure the outputs on screen: each level keeps its geometric max_screen_pixels\n"
                                              "(error under half a pixel) and there is no chain (needs no GL driver)"},
                    {"measure-views", 0, "N", "4", "directions each output and the input are drawn from when measured, by the engine method,\n"
                                                   "at 256, 128, 64, 32 and 16 px, then doubling up to 1024 px while a file holds, against\n"
                                                   "the truth (the input drawn once per view at 2x the size, box-filtered down). A file's\n"
                                                   "max_screen_pixels is the largest of those sizes at which it\n"
                                                   "holds: as good as the input itself as an engine draws it there (footprint PSNR within\n"
                                                   "--hold-psnr, soft IoU within 0.1, coverage within 0.3 of it and at least half the\n"
                                                   "truth's; manifest measuring)"},
                    {"hold-psnr", 0, "DB", "2", "how far a file's footprint PSNR may fall below the input as drawn at a size and still hold"},
                    {"no-chain", 0, "", "", "no recommended chain (manifest recommended_chain, made by default): nearest first, the\n"
                                            "input itself above the largest size measured; then per band the smallest file that holds\n"
                                            "there, never more bytes than a nearer file (nor than the input, unless it draws better);\n"
                                            "where none holds, the input itself (or, where it costs more than the nearer band's file,\n"
                                            "the best PSNR less 1 dB per doubling of bytes, with the reason); switch distances for\n"
                                            "--lod-screen-height at a 60 degree field of view; with --lod-file, STEM_lods.glb holds the\n"
                                            "chain's files. Without it the mesh LODs are not measured"},
                    {"no-report-html", 0, "", "", "do not write report.html, the bake's page for a browser (written by default: self-contained,\n"
                                                  "the input beside every output drawn by the engine method at its own on-screen size and at\n"
                                                  "256 px, per file bytes, texels, GPU bytes and measured error, the chain as bands, the\n"
                                                  "warnings; without a GL driver it has no images and says so)"},
                    {"max-memory", 0, "SIZE", "the memory available: the least of MemAvailable, the cgroup's limit, QF_MEMORY_LIMIT", "the memory the bake may take (bytes, or 512M, 4G: powers of 1024). A point set\n"
                                                                         "whose estimated need (384 MB + 1.35 x (440 + 8 k) bytes a point) is larger bakes out of core:\n"
                                                                         "decomposed on a subsample that fits, its textures resampled from every point, read\n"
                                                                         "back in tiles from a scratch file in $TMPDIR (removed at the end, on Ctrl-C and on\n"
                                                                         "SIGTERM); LAS/LAZ and point-only PLY are read a block at a time, never whole; manifest\n"
                                                                         "out_of_core, report memory. A mesh past it is refused (bake.memory)"},
                    {"asset-root", 0, "DIR", "the input's folder", "the folder the input's external files (glTF buffers and images, OBJ mtllib,\n"
                                                                       "MTL map_Kd) must resolve inside, symlinks followed; a reference leading outside it,\n"
                                                                       "or naming a folder, FIFO or device, is refused (exit 1)"},
                    drop_nonfinite_option(),
                    {"outliers", 0, "F", "10", "point sets: drop the points farther than F x the median spacing from their 8 nearest\n"
                                              "neighbours (mean distance): strays and a scanner's mixed pixels, which would veil the\n"
                                              "coarse levels; the measuring's truth drops them too (report dropped_outliers); out of\n"
                                              "core judged on the subsample and each point's links to it; 0 keeps every point"},
                    {"quiet", 'q', "", "", "no progress and no summary on stderr (progress: on a terminal one line, redrawn;\n"
                                           "otherwise a line every 5 s or QF_PROGRESS_SECONDS: the step running and its count)"}},
                   1, 1};
  append_point_input_options(spec.options);
  return spec;
}

namespace {

// --webp-color / --webp-normal: "lossless" or a lossy quality 1..100; the rest of `fallback` (exact
// alpha, effort) stays as measured.
WebpOptions read_webp_setting(const OptionValues& args, const std::string& name, WebpOptions fallback) {
  if (!args.has(name)) return fallback;
  if (args.get(name) == "lossless") {
    fallback.lossless = true;
    fallback.quality = 75;  // libwebp's default effort
    return fallback;
  }
  fallback.lossless = false;
  fallback.quality = static_cast<int>(args.get_int(name, fallback.quality, 1, 100));
  return fallback;
}

}  // namespace

AssetOptions read_asset_options(const OptionValues& args) {
  AssetOptions a;
  a.tool_version = version();
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
  o.gltf.textures = parse_textures(args.get_choice("textures", {"png", "ktx2", "webp"}, textures_name(o.gltf.textures)));
  o.gltf.color_codec = parse_basis_codec(args.get_choice("ktx2-color", {"etc1s", "uastc"}, basis_codec_name(o.gltf.color_codec)));
  o.gltf.normal_codec = parse_basis_codec(args.get_choice("ktx2-normal", {"etc1s", "uastc"}, basis_codec_name(o.gltf.normal_codec)));
  o.gltf.etc1s_quality = static_cast<int>(args.get_int("ktx2-quality", o.gltf.etc1s_quality, 1, 255));
  if (o.gltf.textures != GltfOptions::Textures::kKtx2 && (args.has("ktx2-color") || args.has("ktx2-normal") || args.has("ktx2-quality")))
    throw UsageError("--ktx2-color, --ktx2-normal and --ktx2-quality need --textures ktx2");
  o.gltf.webp_color = read_webp_setting(args, "webp-color", o.gltf.webp_color);
  o.gltf.webp_normal = read_webp_setting(args, "webp-normal", o.gltf.webp_normal);
  if (o.gltf.textures != GltfOptions::Textures::kWebp && (args.has("webp-color") || args.has("webp-normal")))
    throw UsageError("--webp-color and --webp-normal need --textures webp");
  if (args.has("levels") && args.has("primitives")) throw UsageError("give --levels or --primitives, not both");
  if (args.has("levels")) {
    o.levels = args.get_int_list("levels", std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
  } else if (args.has("primitives")) {
    o.primitives.clear();
    for (long long n : args.get_int_list("primitives", 1, std::numeric_limits<long long>::max()))
      o.primitives.push_back(static_cast<std::size_t>(n));
  }
  if (args.flag("aim-primitives")) {
    if (args.has("levels")) throw UsageError("--aim-primitives aims the levels at --primitives; it does not go with --levels");
    o.amg.target_sizes = o.primitives;
    std::sort(o.amg.target_sizes.rbegin(), o.amg.target_sizes.rend());
    o.amg.target_sizes.erase(std::unique(o.amg.target_sizes.begin(), o.amg.target_sizes.end()), o.amg.target_sizes.end());
  }
  o.cache_dir = read_cache_dir(args);
  if (args.has("max-memory")) {
    const std::string v = args.get("max-memory");
    try {
      o.max_memory = parse_byte_size(v);
    } catch (const std::invalid_argument&) {
      throw UsageError("--max-memory: expected a size in bytes, or with K, M, G or T (powers of 1024), e.g. 4G; got '" + v + "'");
    }
    if (o.max_memory == 0) throw UsageError("--max-memory: a bake needs more than 0 bytes; got '" + v + "'");
  }
  a.lod_file = args.flag("lod-file");
  a.lod_screen_height = args.get_double("lod-screen-height", a.lod_screen_height, 1.0, 100000.0);
  a.read.drop_nonfinite = args.flag("drop-nonfinite");
  a.read.asset_root = args.has("asset-root") ? args.get("asset-root") : "";
  a.read.memory_limit = o.max_memory;
  a.read.outlier_factor = static_cast<float>(args.get_double("outliers", 10.0, 0.0, 1e6));
  a.sample = read_sample_options(args);
  a.sample.memory_limit = o.max_memory;
  a.point_seed = static_cast<std::uint64_t>(args.get_int("point-seed", 1, 0, 1ll << 62));
  a.point_impostor = args.flag("points");
  a.cheap_triangles = static_cast<std::size_t>(args.get_int("cheap-triangles", static_cast<long long>(a.cheap_triangles), 0, 1ll << 40));
  for (const char* name : {"ldi", "sampler", "all-triangles", "visibility-views", "point-seed", "points", "cheap-triangles"})
    if (args.has(name)) a.mesh_only_given.push_back(std::string("--") + name);
  const std::string lods = args.flag("no-mesh-lods") ? "none" : args.get_choice("mesh-lods", {"simplify", "clustering", "none"}, "simplify");
  a.mesh_lods = lods == "simplify" ? AssetOptions::MeshLods::kSimplify
                : lods == "clustering" ? AssetOptions::MeshLods::kClustering
                                       : AssetOptions::MeshLods::kNone;
  render::MeasureOptions measure;
  measure.views = static_cast<int>(args.get_int("measure-views", measure.views, 1, 1000));
  measure.read = a.read;
  a.chain = !args.flag("no-chain");
  a.chain_rule.bar.psnr_drop = args.get_double("hold-psnr", a.chain_rule.bar.psnr_drop, 0.0, 99.0);
  a.chain_rule.screen_height = a.lod_screen_height;
  if (args.flag("no-measure") && (args.has("hold-psnr") || args.has("measure-views")))
    throw UsageError("--no-measure leaves nothing for --hold-psnr or --measure-views to do");
  if (!args.flag("no-measure")) a.measure = measure;
  if (!args.flag("no-report-html")) {
    render::BakePageOptions page;
    page.read = a.read;
    a.report_page = [page](const AssetBake& bake, const std::string& input) { return render::bake_page(bake, input, page); };
  }
  return a;
}

void print_bake_summary(const AssetBake& a, const std::string& in, const std::string& outdir) {
  const BakeResult& r = a.result;
  std::fprintf(stderr, "qf-bake: %s (%zu points) -> %s, hierarchy of %zu levels (cache: %s)\n", in.c_str(), r.points,
               outdir.c_str(), r.hierarchy_levels, r.cache.c_str());
  if (a.read.dropped_outliers) std::fprintf(stderr, "  %zu outliers dropped (--outliers)\n", a.read.dropped_outliers);
  if (r.memory.out_of_core)
    std::fprintf(stderr, "  out of core (about %s needed, %s of %s): decomposed on %zu of the points, textured from all of them "
                         "(scratch %s, removed)\n",
                 format_bytes(double(r.memory.need)).c_str(), format_bytes(double(r.memory.limit)).c_str(), r.memory.limit_source.c_str(),
                 r.memory.subsample, format_bytes(double(r.scratch_bytes)).c_str());
  for (const BakedLevel& l : r.levels)
    std::fprintf(stderr, "  level %zu: %zu primitives, %zu texels, error %.3g (%.2g of the diagonal)\n", l.level, l.primitives,
                 l.textures.texels, l.error, l.relative_error);
  double total = 0;
  for (const StageTime& t : r.times) total += t.seconds;
  std::fprintf(stderr, "  time: %.3f s, %zu files\n", total + a.sampled.seconds, a.files.size() + 2);
  if (!a.sampled.backend.empty())
    std::fprintf(stderr, "  sampled: %s, pixel %.4g, layers %d/%d/%d, %.3f s\n", a.sampled.backend.c_str(), a.sampled.pixel,
                 a.sampled.layers[0], a.sampled.layers[1], a.sampled.layers[2], a.sampled.seconds);
  if (a.manifest.contains("recommended_chain")) {
    // The chain, nearest first: each file down to the on-screen size it is shown to, its error there.
    std::fprintf(stderr, "  recommended chain:");
    const char* sep = " ";
    for (const nlohmann::json& e : a.manifest["recommended_chain"]["chain"]) {
      // The input's first entry, above the largest size measured, has no figure (error null).
      char figure[64] = "";
      if (e["error"].is_object() && e["error"]["psnr"].is_number())
        std::snprintf(figure, sizeof figure, " (%.1f dB%s)", e["error"]["psnr"].get<double>(), e["bar_met"].get<bool>() ? "" : ", under the bar");
      std::fprintf(stderr, "%s%s to %d px%s", sep, e["kind"] == "asset" ? "the input" : e["file"].get<std::string>().c_str(), e["min_pixels"].get<int>(),
                   figure);
      sep = ", ";
    }
    std::fprintf(stderr, "\n");
  }
  for (const std::string& w : r.warnings) std::fprintf(stderr, "  warning: %s\n", w.c_str());
}

// Seconds between progress lines in a log: QF_PROGRESS_SECONDS, default 5.
double progress_seconds() {
  const char* v = std::getenv("QF_PROGRESS_SECONDS");
  if (!v || !*v) return 5;
  char* end = nullptr;
  const double s = std::strtod(v, &end);
  if (*end || !(s >= 0.01 && s <= 86400))
    throw UsageError(std::string("QF_PROGRESS_SECONDS: expected seconds between progress lines (0.01 to 86400), got '") + v + "'");
  return s;
}

int run_bake(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  const std::string outdir = args.require("output");
  const AssetOptions options = read_asset_options(args);
  // Taken before any work: a second bake into the folder is refused at once (exit 5), not after
  // minutes of baking.
  OutputFolder out(outdir);
  AssetBake a;
  {
    // A bake of millions of points runs for minutes: its steps on stderr while it runs.
    const progress::ProgressDisplay shown(stderr, ::isatty(2) != 0, !args.flag("quiet"), "qf-bake bake", progress_seconds());
    a = bake_asset(in, options, in);
    progress::step("writing " + outdir);
    write_asset(out, a.files, a.manifest, a.report, a.page);
  }
  if (!args.flag("quiet")) print_bake_summary(a, in, outdir);
  return 0;
}

}  // namespace qf::cli
