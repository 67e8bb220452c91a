// The mesh LODs of one asset (pipeline/mesh_lods.h) and the LOD files `qf-bake simplify` and
// `cluster` write (pipeline/asset.h): meshoptimizer's edge collapse or seed 002's vertex clustering.
#include "pipeline/mesh_lods.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <omp.h>
#include <stdexcept>

#include "core/error.h"
#include "gltf/glb.h"
#include "reconstruct/reconstruct.h"
#include "simplify/simplify.h"

namespace qf {

std::vector<double> default_cluster_cells(const TriangleMesh& mesh) {
  std::vector<double> cells;
  for (double f : {128.0, 64.0, 32.0, 16.0, 8.0}) cells.push_back(mesh.bounds().diagonal() / f);
  return cells;
}

std::vector<std::size_t> default_simplify_budgets(const TriangleMesh& mesh) {
  std::vector<std::size_t> budgets;
  for (std::size_t d = 4; d <= 1024; d *= 4)
    if (mesh.triangles.size() / d >= 16) budgets.push_back(mesh.triangles.size() / d);
  return budgets;
}

namespace {

// Whether two LODs are the same mesh: the same vertices, triangles and surface.
bool same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  const auto same_uvs = [](const std::array<Vec2f, 3>& x, const std::array<Vec2f, 3>& y) {
    for (std::size_t k = 0; k < 3; ++k)
      if (x[k].x != y[k].x || x[k].y != y[k].y) return false;
    return true;
  };
  return a.triangles == b.triangles && a.triangle_materials == b.triangle_materials && a.positions == b.positions &&
         a.normals == b.normals && a.colors == b.colors && a.corner_uvs.size() == b.corner_uvs.size() &&
         std::equal(a.corner_uvs.begin(), a.corner_uvs.end(), b.corner_uvs.begin(), same_uvs);
}

// One LOD's file and manifest entry (`s` is finished for writing: normals, textures, sidedness).
nlohmann::json simplify_level_file(SimplifiedMesh& s, std::size_t budget, double diagonal, bool collapsed, const std::string& name,
                                   std::vector<OutputFile>& files, bool smooth, const GltfOptions& gltf) {
  // A mesh with materials (textured glTF, OBJ + MTL) keeps them, its textures sized for the
  // level's screen: at most 2 x max_screen_pixels texels a side (the spider's 768-px texture in
  // its 3-px level cost 1.4 MB; at its 342-triangle level, drawn at its 43 px, sides of 4x, 2x
  // and 1x scored 16.25, 16.24 and 16.12 dB in 100, 39 and 22 KB); others get the LOD material.
  const double max_screen_pixels = s.error > 0 ? std::min(0.5 * diagonal / s.error, 1e9) : 1e9;
  const bool own_materials = !s.mesh.materials.empty();
  // Normals as the input's reference is drawn: its own where it has them (carried through the
  // simplifier), else smooth or none (flat).
  if (own_materials && smooth && s.mesh.normals.empty()) s.mesh.normals = s.mesh.smooth_normals();
  if (own_materials) fit_textures(s.mesh, static_cast<int>(std::min(2 * max_screen_pixels, 2.0 * kLargestMeasuredPixels)));
  // Double-sided, as the LOD material and the impostor levels are, where triangles were collapsed:
  // a collapsed thin part (a leg, a leaf) may show its back faces. All kept, the input's sidedness
  // stays (2CylinderEngine's copy, double-sided, showed the backs of its open parts: 56.4 dB).
  if (collapsed)
    for (SurfaceMaterial& m : s.mesh.materials) m.double_sided = true;
  // Its textures in the bake's format where that is KTX2 (PNG else): what they cost is said beside
  // the bytes, as the impostor levels' (the GPU memory KTX2 saves).
  TextureCost cost;
  files.push_back({name, own_materials ? encode_textured_mesh_glb(s.mesh, gltf, &cost) : encode_mesh_glb(s.mesh, smooth)});
  nlohmann::json entry{{"file", name},
                       {"target_triangles", budget},
                       {"triangles", s.mesh.triangles.size()},
                       {"vertices", s.mesh.positions.size()},
                       {"bytes", files.back().bytes.size()},
                       {"error", canonical_double(static_cast<float>(s.error))},
                       {"max_screen_pixels", static_cast<long long>(max_screen_pixels)}};
  if (cost.texels > 0) entry["texture_bytes"] = cost.file_bytes, entry["gpu_bytes"] = cost.gpu_bytes;
  return entry;
}

// Why the LODs stop above their budgets, in this mesh's own figures: where the simplifier stalled,
// the file that holds that mesh, and the budgets it left untried.
std::string stall_message(const char* simplifier, std::size_t stalled_at, std::size_t budget, std::size_t input_triangles,
                          const std::string& file, const std::vector<std::size_t>& untried) {
  std::string m = std::string(simplifier) + " stalled at " + std::to_string(stalled_at) + " of the input's " +
                  std::to_string(input_triangles) + " triangles (budget " + std::to_string(budget) +
                  "): no collapse left keeps the topology (thin parts, separate pieces, creases), so " + file + " is the coarsest mesh LOD";
  if (untried.empty()) return m;
  std::string list;
  for (std::size_t b : untried) list += (list.empty() ? "" : ", ") + std::to_string(b);
  return m + " and the smaller budget" + (untried.size() > 1 ? "s " : " ") + list + " would give it again (not tried)";
}

}  // namespace

nlohmann::json simplify_level_files(const TriangleMesh& mesh, const std::vector<std::size_t>& budgets, const std::string& stem,
                                    std::vector<OutputFile>& files, bool smooth, SimplifyMethod method, const GltfOptions& gltf) {
  const double diagonal = mesh.bounds().diagonal();
  const char* simplifier = method == SimplifyMethod::kSloppy ? "simplifySloppy" : "simplify";
  nlohmann::json levels = nlohmann::json::array(), skipped = nlohmann::json::array();
  std::size_t stalled_at = 0, stalled_budget = 0;  // triangles and budget where the simplifier stalled; 0: it did not
  std::vector<std::size_t> untried;                // the budgets not tried after it
  std::size_t vanished_at = 0;                     // the budget at which collapse took the whole mesh away; 0: none
  TriangleMesh previous;  // the last written LOD's mesh, as simplified
  std::string previous_name;
  for (std::size_t i = 0; i < budgets.size(); ++i) {
    if (stalled_at > 0) {
      skipped.push_back({{"target_triangles", budgets[i]}, {"skipped", std::string("not tried: ") + simplifier + " stalled above a larger budget (see stopped)"}});
      untried.push_back(budgets[i]);
      continue;
    }
    if (vanished_at > 0) {
      skipped.push_back({{"target_triangles", budgets[i]},
                         {"skipped", "not tried: simplify took the whole mesh away at the larger budget " + std::to_string(vanished_at)}});
      continue;
    }
    SimplifiedMesh s = simplify_mesh(mesh, budgets[i], method);
    // Edge collapse may take a thin mesh away whole below some budget (permissive collapse: the
    // generated lattice below 16 triangles): the smaller budgets are not tried, the bake goes on.
    if (s.mesh.triangles.empty() && method == SimplifyMethod::kCollapse) {
      vanished_at = budgets[i];
      skipped.push_back({{"target_triangles", budgets[i]}, {"skipped", "simplify collapsed the whole mesh"}});
      continue;
    }
    // simplifySloppy may cluster a small budget's mesh away entirely (2CylinderEngine at 52).
    if (s.mesh.triangles.empty())
      throw UsageError("a budget of " + std::to_string(budgets[i]) + " triangles leaves nothing of this mesh (" + simplifier +
                       " collapsed it whole); give a larger one");
    // 1. Above its budget, the simplifier has stalled: no collapse is left that keeps the topology
    //    (thin beams, many parts, vertices split at creases and seams), and every smaller budget
    //    would give this mesh again. simplifySloppy as the fallback was measured and not taken
    //    (engine method, 8 views, 128 px, against the input): 2CylinderEngine's stalled 33,008
    //    triangles score 25.8 dB, IoU 0.996; sloppy at 6,182 and 1,307 triangles 12.9 dB, 0.976 and
    //    11.9 dB, 0.915; the lattice's stalled 224 triangles IoU 0.24, sloppy at 54 IoU 0.10 (all
    //    with meshoptimizer 0.18; with 1.2's permissive collapse 2CylinderEngine stalls at 6,558
    //    triangles, 16.2 dB, IoU 0.938, still ahead of sloppy in PSNR). That is why the message
    //    offers no fallback; it names this mesh's own figures only.
    if (s.mesh.triangles.size() > budgets[i]) stalled_at = s.mesh.triangles.size(), stalled_budget = budgets[i];
    // 2. The same mesh as the last LOD is not written again.
    if (!levels.empty() && same_mesh(s.mesh, previous)) {
      skipped.push_back({{"target_triangles", budgets[i]}, {"skipped", "same mesh as " + previous_name + ".glb"}});
      continue;
    }
    previous = s.mesh;
    previous_name = stem + "_S" + std::to_string(levels.size());
    const bool collapsed = s.mesh.triangles.size() < mesh.triangles.size();
    levels.push_back(simplify_level_file(s, budgets[i], diagonal, collapsed, previous_name + ".glb", files, smooth, gltf));
  }
  nlohmann::json out{{"levels", levels}};
  if (!skipped.empty()) out["skipped"] = skipped;
  // The stalled mesh is the last one written (every later budget is skipped).
  if (stalled_at > 0) out["stopped"] = stall_message(simplifier, stalled_at, stalled_budget, mesh.triangles.size(), previous_name + ".glb", untried);
  if (vanished_at > 0)
    out["stopped"] = "simplify collapsed the whole mesh at a budget of " + std::to_string(vanished_at) + " triangles: the smaller budgets are not tried";
  return out;
}

nlohmann::json cluster_level_files(const std::vector<LodMesh>& lods, const std::string& stem, bool draco,
                                   std::vector<OutputFile>& files, double diagonal) {
  nlohmann::json levels = nlohmann::json::array();
  for (std::size_t i = 0; i < lods.size(); ++i) {
    const LodMesh& l = lods[i];
    const std::string name = stem + "_C" + std::to_string(i) + ".glb";
    files.push_back({name, encode_cluster_glb(l)});
    levels.push_back({{"file", name},
                      {"cell_width", canonical_double(l.cell)},
                      {"max_screen_pixels", static_cast<long long>(kClusterCellPixels * diagonal / l.cell)},
                      {"vertices", l.positions.size()},
                      {"triangles", l.triangles.size()},
                      {"edges", l.edges.size()},
                      {"points", l.points.size()}});
    if (draco) {
      const std::string dname = stem + "_C" + std::to_string(i) + ".draco.glb";
      const std::size_t plain = files.back().bytes.size();
      files.push_back({dname, encode_cluster_glb(l, {}, true)});
      levels.back()["draco_file"] = dname;
      levels.back()["bytes"] = plain;
      levels.back()["draco_bytes"] = files.back().bytes.size();
    }
  }
  return levels;
}

nlohmann::json mesh_lod_outputs(const TriangleMesh& mesh, const AssetOptions& o, const std::string& stem,
                                std::vector<OutputFile>& files, bool smooth) {
  if (o.mesh_lods == AssetOptions::MeshLods::kClustering) {
    const VertexGrading grading = grade_vertices(mesh);
    ClusterOptions co;
    std::vector<LodMesh> lods;
    for (double c : default_cluster_cells(mesh)) {
      co.cell = static_cast<float>(c);
      lods.push_back(cluster_mesh(mesh, grading, co));
    }
    return {{"method", "clustering"},
            {"levels", cluster_level_files(lods, stem, false, files, mesh.bounds().diagonal())},
            {"lod_rule", "largest cell_width <= X * R, R = 2 D tan(fov/2) / window height, X = 5 (max_screen_pixels = X D / cell_width); "
                         "thick line width = _THICKNESS / R pixels"}};
  }
  if (o.mesh_lods == AssetOptions::MeshLods::kSimplify && !default_simplify_budgets(mesh).empty()) {
    // The textures in the impostor levels' format where it is KTX2 (--textures ktx2), with every
    // thread the encoder's (its bytes do not depend on it).
    GltfOptions gltf = o.bake.gltf;
    gltf.threads = omp_get_max_threads();
    nlohmann::json lods = simplify_level_files(mesh, default_simplify_budgets(mesh), stem, files, smooth, SimplifyMethod::kCollapse, gltf);
    lods["method"] = "simplify";
    lods["lod_rule"] = "coarsest level whose max_screen_pixels >= the object's on-screen size (bounding-box diagonal, pixels)";
    return lods;
  }
  return nullptr;
}

nlohmann::json reconstructed_lod_outputs(const PointSet& points, const AssetOptions& o, const std::string& stem,
                                         std::vector<OutputFile>& files, std::vector<std::string>& warnings) {
  if (o.mesh_lods != AssetOptions::MeshLods::kSimplify) return nullptr;
  Reconstruction rec;
  try {
    rec = reconstruct_surface(points);
  } catch (const std::invalid_argument& e) {
    warnings.push_back(std::string("no mesh LODs: the points could not be reconstructed into a surface (") + e.what() + ")");
    return nullptr;
  }
  if (default_simplify_budgets(rec.mesh).empty()) return nullptr;
  nlohmann::json lods = simplify_level_files(rec.mesh, default_simplify_budgets(rec.mesh), stem, files, true);
  lods["method"] = "simplify";
  lods["lod_rule"] = "coarsest level whose max_screen_pixels >= the object's on-screen size (bounding-box diagonal, pixels)";
  lods["reconstruction"] = {{"method", "advancing front (CGAL)"},
                            {"points_used", rec.points_used},
                            {"triangles", rec.mesh.triangles.size()}};
  return lods;
}

namespace {

// "footprint PSNR 19.8 dB, soft IoU 0.218" of a measured entry; empty where either is missing.
std::string psnr_iou(const nlohmann::json& e) {
  if (!e.is_object() || !e.contains("psnr") || !e["psnr"].is_number() || !e.contains("soft_iou") || !e["soft_iou"].is_number()) return "";
  char text[64];
  std::snprintf(text, sizeof text, "%.1f dB, soft IoU %.3f", e["psnr"].get<double>(), e["soft_iou"].get<double>());
  return text;
}

// The entry of `measured` (a list of {pixels, ...}) at `pixels`; null when none.
const nlohmann::json* at_pixels(const nlohmann::json& measured, long long pixels) {
  for (const nlohmann::json& e : measured)
    if (e.value("pixels", 0LL) == pixels) return &e;
  return nullptr;
}

}  // namespace

std::string stalled_lods_warning(const nlohmann::json& manifest) {
  if (!manifest.contains("mesh_lods") || !manifest["mesh_lods"].contains("stopped")) return "";
  const nlohmann::json& lods = manifest["mesh_lods"];
  std::string w = "mesh LODs: " + lods["stopped"].get<std::string>();
  if (!lods.contains("levels") || lods["levels"].empty()) return w;
  const nlohmann::json& lod = lods["levels"].back();
  if (!lod.contains("measured") || lod["measured"].empty()) return w;
  // The bake's own measuring of the stalled LOD (the coarsest): how far it holds, and its figures
  // beside the input's as drawn at that size (at the largest size measured where it holds at none).
  const long long holds_to = lod.value("max_screen_pixels", 0LL);
  const long long pixels = holds_to > 0 ? holds_to : lod["measured"][0].value("pixels", 0LL);
  const nlohmann::json* own = at_pixels(lod["measured"], pixels);
  const nlohmann::json* input = manifest.contains("measuring") && manifest["measuring"].contains("asset")
                                    ? at_pixels(manifest["measuring"]["asset"], pixels) : nullptr;
  w += "; measured as an engine draws it, " + lod.at("file").get<std::string>() +
       (holds_to > 0 ? " holds up to " + std::to_string(pixels) + " px" : std::string(" holds at no size measured"));
  const std::string figures = own ? psnr_iou(*own) : "";
  if (figures.empty()) return w;
  w += " (at " + std::to_string(pixels) + " px: footprint PSNR " + figures;
  if (const std::string asset = input ? psnr_iou(*input) : ""; !asset.empty()) w += "; the input as drawn " + asset;
  return w + ")";
}

}  // namespace qf
