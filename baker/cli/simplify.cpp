// The simplify command: a triangle mesh in, edge-collapse LODs out (meshoptimizer), one .glb per
// triangle budget and a manifest with each LOD's triangles and error. Written like the bake:
// staged, manifest last.
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "cli/commands.h"
#include "core/error.h"
#include "pipeline/asset.h"

namespace qf::cli {

CommandSpec simplify_spec() {
  return {"simplify", "MESH -o OUTDIR --triangles N,N,... [options]",
          "simplify a triangle mesh by edge collapse (meshoptimizer) into one .glb per triangle budget",
          "Each LOD comes from the original mesh: edges are collapsed by quadric error until the budget\n"
          "is met or no collapse keeps the topology. Vertex colours are kept; STEM_S<i>.glb holds the\n"
          "triangles with the input's own normals (kept through the simplifier: hard edges stay hard) or,\n"
          "for a mesh without, smooth normals (or none with --normals flat: engines then shade each triangle\n"
          "flat). A budget whose LOD is the same mesh as the last one is skipped, and where the simplifier\n"
          "stalls above a budget the smaller ones are not tried (manifest: skipped, stopped). manifest.json\n"
          "gives each LOD's triangles, vertices, bytes, meshoptimizer's error and the\n"
          "largest on-screen size at which that error stays under half a pixel.",
          {output_option("OUTDIR", "output folder (created if needed); required"),
           {"triangles", 't', "N,N,...", "", "triangle budgets, one LOD each; required"},
           {"normals", 0, "smooth|flat", "flat for glTF, else smooth",
            "for a mesh without normals of its own: vertex normals area-weighted over the LOD's triangles, or none\n"
            "(a mesh's own normals are always kept)"},
           {"method", 0, "collapse|sloppy", "collapse",
            "meshoptimizer's edge collapse (simplify: keeps the topology), or simplifySloppy (clusters vertices\n"
            "on a grid: reaches any budget, merging thin parts and pieces)"},
           drop_nonfinite_option(), quiet_option()},
          1, 1};
}

int run_simplify(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  const std::string outdir = args.require("output");
  args.require("triangles");

  const bool sloppy = args.get_choice("method", {"collapse", "sloppy"}, "collapse") == "sloppy";
  std::vector<std::size_t> budgets;
  for (long long n : args.get_int_list("triangles", 1, std::numeric_limits<long long>::max())) budgets.push_back(static_cast<std::size_t>(n));
  ReadOptions ro;
  ro.drop_nonfinite = args.flag("drop-nonfinite");
  ReadReport read;
  const Model model = read_model(in, ro, &read);
  // Without --normals, the LODs are drawn as the input is (qf-bake's bake does the same).
  const std::string normals =
      args.get_choice("normals", {"smooth", "flat"}, read.format == "glb" || read.format == "gltf" ? "flat" : "smooth");
  if (!model.is_mesh) throw InputError("simplify.needs_mesh", in, "", "is a point set; simplify takes triangle meshes (.off, .obj, .ply with faces)");
  if (model.mesh.triangles.empty()) throw InputError("mesh.no_triangles", in, "", "is a mesh without triangles; nothing to simplify");

  const auto start = std::chrono::steady_clock::now();
  const std::string stem = std::filesystem::path(in).stem().string();
  std::vector<OutputFile> files;
  const nlohmann::json lods = simplify_level_files(model.mesh, budgets, stem, files, normals == "smooth",
                                                    sloppy ? SimplifyMethod::kSloppy : SimplifyMethod::kCollapse);
  const nlohmann::json& levels = lods["levels"];
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json manifest{{"input", in},
                                {"triangles", model.mesh.triangles.size()},
                                {"vertices", model.mesh.positions.size()},
                                {"method", sloppy ? "meshoptimizer simplifySloppy (vertex clustering, topology not kept)"
                                                  : "meshoptimizer simplify (edge collapse, quadric error)"},
                                {"normals", normals},
                                {"levels", levels},
                                {"generator", "quasiflat qf-bake simplify"}};
  for (const char* key : {"skipped", "stopped"})
    if (lods.contains(key)) manifest[key] = lods[key];
  OutputFolder out(outdir);
  write_asset(out, files, manifest, nullptr);
  if (!args.flag("quiet")) {
    std::fprintf(stderr, "qf-bake simplify: %s (%zu triangles) -> %s, %zu LODs in %.3f s\n", in.c_str(), model.mesh.triangles.size(),
                 outdir.c_str(), levels.size(), seconds);
    if (lods.contains("stopped")) std::fprintf(stderr, "  stopped: %s\n", lods["stopped"].get<std::string>().c_str());
    for (const auto& l : levels)
      std::fprintf(stderr, "  %s: %zu triangles, error %.4g\n", l["file"].get<std::string>().c_str(), l["triangles"].get<std::size_t>(),
                   l["error"].get<double>());
  }
  return 0;
}

}  // namespace qf::cli
