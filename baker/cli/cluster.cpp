// The cluster command: a triangle mesh in, a chain of vertex-clustering LOD meshes out (seed 002),
// one .glb per cell width and a manifest. Written into a private folder and moved into place,
// manifest last, like the bake.
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <chrono>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "clustering/clustering.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/file_io.h"
#include "pipeline/asset.h"

namespace qf::cli {

CommandSpec cluster_spec() {
  return {"cluster", "MESH -o OUTDIR [options]",
          "simplify a triangle mesh into vertex-clustering LODs with thick edges (one .glb per cell width)",
          "Vertices are graded (cos(theta/2) x longest incident edge), visited heaviest first, and grouped\n"
          "by floating cells centred on them; triangles collapsing to an edge become thick lines (glTF\n"
          "LINES with a _THICKNESS attribute), to a vertex points. Every level comes from the original mesh.\n"
          "manifest.json gives each level's cell width: a runtime picks the largest cell <= X * R, with\n"
          "R = 2 D tan(fov/2) / window height (X = 5..10), and draws thick lines thickness / R pixels wide.",
          {output_option("OUTDIR", "output folder (created if needed); required"),
           {"cells", 0, "W,W,...", "diagonal/128,/64,/32,/16,/8", "cell widths in model units"},
           {"shape", 0, "cube|sphere", "cube", "cell shape"},
           {"assign", 0, "nearest|heaviest", "nearest", "a vertex inside several cells joins the nearest centre (paper 3.2.3) or the heaviest"},
           {"uniform", 0, "", "", "Rossignac-Borrel uniform grid clustering instead of floating cells (for comparison)"},
           {"draco", 0, "", "", "also write STEM_C<i>.draco.glb: triangles Draco-compressed (KHR_draco_mesh_compression, required)"},
           drop_nonfinite_option(), quiet_option()},
          1, 1};
}

int run_cluster(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  const std::string outdir = args.require("output");
  ClusterOptions o;
  const std::string shape = args.get_choice("shape", {"cube", "sphere"}, "cube");
  const std::string assign = args.get_choice("assign", {"nearest", "heaviest"}, "nearest");
  o.shape = shape == "cube" ? ClusterOptions::Shape::kCube : ClusterOptions::Shape::kSphere;
  o.assign = assign == "nearest" ? ClusterOptions::Assign::kNearest : ClusterOptions::Assign::kHeaviest;
  o.uniform = args.flag("uniform");
  // Cell widths in model units: positive (the smallest positive double is the bound, 0 excluded).
  std::vector<double> cells = args.get_double_list("cells", std::numeric_limits<double>::min(), std::numeric_limits<double>::max());
  ReadOptions ro;
  ro.drop_nonfinite = args.flag("drop-nonfinite");
  ReadReport report;
  const Model model = read_model(in, ro, &report);
  if (!model.is_mesh) throw InputError("cluster.needs_mesh", in, "", "is a point set; cluster simplifies triangle meshes (.off, .obj, .ply with faces)");
  const TriangleMesh& mesh = model.mesh;
  if (mesh.triangles.empty()) throw InputError("mesh.no_triangles", in, "", "is a mesh without triangles; nothing to simplify");
  const float diagonal = mesh.bounds().diagonal();
  if (cells.empty()) cells = default_cluster_cells(mesh);

  const auto start = std::chrono::steady_clock::now();
  const VertexGrading grading = grade_vertices(mesh);
  std::vector<LodMesh> lods;
  for (double c : cells) {
    o.cell = static_cast<float>(c);
    lods.push_back(cluster_mesh(mesh, grading, o));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::string stem = std::filesystem::path(in).stem().string();
  std::vector<OutputFile> files;
  const nlohmann::json levels = cluster_level_files(lods, stem, args.flag("draco"), files, diagonal);
  const nlohmann::json manifest{{"input", in},
                                {"triangles", mesh.triangles.size()},
                                {"vertices", mesh.positions.size()},
                                {"bounding_box_diagonal", canonical_double(diagonal)},
                                {"method", o.uniform ? "uniform" : "floating"},
                                {"shape", shape},
                                {"assign", assign},
                                {"lod_rule", "largest cell_width <= X * R, R = 2 D tan(fov/2) / window height, X = 5; "
                                             "thick line width = _THICKNESS / R pixels"},
                                {"levels", levels},
                                {"generator", "quasiflat qf-bake cluster"}};
  OutputFolder out(outdir);
  write_asset(out, files, manifest, nullptr);
  if (!args.flag("quiet")) {
    std::fprintf(stderr, "qf-bake cluster: %s (%zu triangles) -> %s, %zu levels in %.3f s\n", in.c_str(), mesh.triangles.size(),
                 outdir.c_str(), lods.size(), seconds);
    for (const LodMesh& l : lods)
      std::fprintf(stderr, "  cell %.4g: %zu triangles, %zu thick edges, %zu points\n", l.cell, l.triangles.size(), l.edges.size(),
                   l.points.size());
  }
  return 0;
}

}  // namespace qf::cli
