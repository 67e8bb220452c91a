// The cluster command: a triangle mesh in, a chain of vertex-clustering LOD meshes out (seed 002),
// one .glb per cell width and a manifest. Written into a private folder and moved into place,
// manifest last, like the bake.
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "clustering/clustering.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/file_io.h"
#include "gltf/glb.h"

namespace qf::cli {

std::vector<double> default_cluster_cells(const TriangleMesh& mesh) {
  std::vector<double> cells;
  for (double f : {128.0, 64.0, 32.0, 16.0, 8.0}) cells.push_back(mesh.bounds().diagonal() / f);
  return cells;
}

nlohmann::json write_cluster_levels(const std::vector<LodMesh>& lods, const std::string& dir, const std::string& stem,
                                    std::vector<std::string>& files, bool draco) {
  nlohmann::json levels = nlohmann::json::array();
  for (std::size_t i = 0; i < lods.size(); ++i) {
    const LodMesh& l = lods[i];
    const std::string name = stem + "_C" + std::to_string(i) + ".glb";
    const std::vector<std::uint8_t> glb = encode_cluster_glb(l);
    write_bytes_atomically(dir + "/" + name, glb);
    files.push_back(name);
    levels.push_back({{"file", name},
                      {"cell_width", canonical_double(l.cell)},
                      {"vertices", l.positions.size()},
                      {"triangles", l.triangles.size()},
                      {"edges", l.edges.size()},
                      {"points", l.points.size()}});
    if (draco) {
      const std::string dname = stem + "_C" + std::to_string(i) + ".draco.glb";
      const std::vector<std::uint8_t> d = encode_cluster_glb(l, {}, true);
      write_bytes_atomically(dir + "/" + dname, d);
      files.push_back(dname);
      levels.back()["draco_file"] = dname;
      levels.back()["bytes"] = glb.size();
      levels.back()["draco_bytes"] = d.size();
    }
  }
  return levels;
}

CommandSpec cluster_spec() {
  return {"cluster", "MESH -o OUTDIR [options]",
          "simplify a triangle mesh into vertex-clustering LODs with thick edges (one .glb per cell width)",
          "Vertices are graded (cos(theta/2) x longest incident edge), visited heaviest first, and grouped\n"
          "by floating cells centred on them; triangles collapsing to an edge become thick lines (glTF\n"
          "LINES with a _THICKNESS attribute), to a vertex points. Every level comes from the original mesh.\n"
          "manifest.json gives each level's cell width: a runtime picks the largest cell <= X * R, with\n"
          "R = 2 D tan(fov/2) / window height (X = 5..10), and draws thick lines thickness / R pixels wide.",
          {{"output", 'o', "OUTDIR", "", "output folder (created if needed); required"},
           {"cells", 0, "W,W,...", "diagonal/128,/64,/32,/16,/8", "cell widths in model units"},
           {"shape", 0, "cube|sphere", "cube", "cell shape"},
           {"assign", 0, "nearest|heaviest", "nearest", "a vertex inside several cells joins the nearest centre (paper 3.2.3) or the heaviest"},
           {"uniform", 0, "", "", "Rossignac-Borrel uniform grid clustering instead of floating cells (for comparison)"},
           {"draco", 0, "", "", "also write STEM_C<i>.draco.glb: triangles Draco-compressed (KHR_draco_mesh_compression, required)"},
           drop_nonfinite_option(),
           {"quiet", 'q', "", "", "print nothing on success"}},
          1, 1};
}

int run_cluster(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  if (!args.has("output")) throw UsageError("cluster needs -o OUTDIR (see qf-bake cluster --help)");
  const std::string outdir = args.get("output");
  ClusterOptions o;
  const std::string shape = args.get("shape", "cube"), assign = args.get("assign", "nearest");
  if (shape != "cube" && shape != "sphere") throw UsageError("--shape must be cube or sphere, got '" + shape + "'");
  if (assign != "nearest" && assign != "heaviest") throw UsageError("--assign must be nearest or heaviest, got '" + assign + "'");
  o.shape = shape == "cube" ? ClusterOptions::Shape::kCube : ClusterOptions::Shape::kSphere;
  o.assign = assign == "nearest" ? ClusterOptions::Assign::kNearest : ClusterOptions::Assign::kHeaviest;
  o.uniform = args.flag("uniform");
  std::vector<double> cells;
  if (args.has("cells")) {
    for (const std::string& t : split_list(args.get("cells"))) {
      char* end = nullptr;
      const double v = std::strtod(t.c_str(), &end);
      if (!end || *end || !(v > 0)) throw UsageError("--cells expects positive numbers separated by commas, got '" + t + "'");
      cells.push_back(v);
    }
  }
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

  write_folder_atomically(outdir, "qf-cluster", [&](const std::string& staging, std::vector<std::string>& files) {
    const std::string stem = std::filesystem::path(in).stem().string();
    const nlohmann::json levels = write_cluster_levels(lods, staging, stem, files, args.flag("draco"));
    nlohmann::json manifest{{"input", in},
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
    write_file_atomically(staging + "/manifest.json", [&](std::ostream& out) { out << manifest.dump(2) << "\n"; });
    files.push_back("manifest.json");
  });
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
