// One asset end to end, the unit of work of `qf-bake bake` and of a batch: an input file (point set
// or mesh) -> the bytes of every output file with the asset's manifest and report -> a folder.
//   point set:  impostor levels (STEM_L<l>.glb), optionally STEM_lods.glb (MSFT_lod)
//   mesh:       sampled into points first (depth peeling), then the same, plus the sampled points
//               as a point impostor (STEM_points.glb) and mesh LODs (STEM_S<i>.glb, or the
//               vertex-clustering STEM_C<i>.glb)
//   both:       every output measured on screen (honest screen sizes), and the recommended chain
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "clustering/clustering.h"
#include "core/output_folder.h"
#include "io/model_io.h"
#include "measure/chain.h"
#include "measure/measure.h"
#include "measure/measurements.h"
#include "measure/screen_sizes.h"
#include "pipeline/bake.h"
#include "sample/sample.h"
#include "simplify/simplify.h"

namespace qf {

struct OutputFile {
  std::string name;  // inside the asset's folder
  std::vector<std::uint8_t> bytes;
};

struct AssetBake;
// Writes the bake's page for people (report.html) from its files, manifest and warnings, drawing
// them (tools/report_html.h; qf-bake hands it over, as it does the measuring). Throws the loaders'
// InputErrors.
using ReportPage = std::function<std::string(const AssetBake& bake, const std::string& input_path)>;

struct AssetOptions {
  BakeOptions bake;
  ReadOptions read;
  SampleOptions sample;          // mesh inputs
  // Mesh inputs: STEM_points.glb, only when asked for: the sampled points outweigh their asset on
  // most meshes (1.4-5.1 MB for real game trees of 1.2-1.7 MB; 12.6 MB for a 4.7 KB textured cube).
  bool point_impostor = false;
  // An opaque mesh of at most this many triangles is cheap already: it is measured, not baked (no
  // files but manifest.json and the reports, which say why; its chain is the asset itself). 0:
  // every mesh is baked. A few hundred triangles draw in one call for less than one level's
  // textures (a textured cube of 12 triangles and 4.7 KB took 28 s and 21.5 MB before).
  std::size_t cheap_triangles = 256;
  std::uint64_t point_seed = 1;  // its permutation
  // Mesh inputs: the mesh LODs beside the impostors. Simplify (meshoptimizer's edge collapse,
  // STEM_S<i>.glb at default_simplify_budgets) by default: in the fidelity league it beats the
  // vertex clustering of seed 002 (STEM_C<i>.glb at default_cluster_cells) in every model x budget
  // case at 256 and 64 pixels, by 1-8 dB, with 4-60x fewer bytes at the same triangle count.
  enum class MeshLods { kSimplify, kClustering, kNone } mesh_lods = MeshLods::kSimplify;
  // Also STEM_lods.glb: the recommended chain's files, else the impostor levels, in one .glb under
  // MSFT_lod (for engines that switch LODs by it). Its screen coverages assume a screen this many
  // pixels high.
  bool lod_file = false;
  double lod_screen_height = 1080;
  // Measures the outputs by drawing them as an engine does (measure/measure.h). With it each
  // measured file's max_screen_pixels is where its look holds beside the asset as drawn
  // (chain_rule.bar, measure/screen_sizes.h) and the manifest keeps every measured figure; none:
  // the geometric sizes, and no chain (no GL driver needed).
  std::optional<render::MeasureOptions> measure;
  // With `measure`, also the recommended chain (manifest recommended_chain, measure/chain.h):
  // the mesh LODs and the point impostor are measured too.
  bool chain = true;
  ChainRule chain_rule;
  // The page (report.html) of the bake; empty: none.
  ReportPage report_page;
  // The options given that only a mesh input uses ("--ldi", ...): a point-set input warns that
  // they were ignored, rather than ignoring them without a word.
  std::vector<std::string> mesh_only_given;
  // The program's version, for report.json (tool_version) and the page; not in the manifest, whose
  // bytes qf-diff compares between a baseline and a new bake (a version change alone is no change
  // of the outputs). Empty: not said.
  std::string tool_version;
};

struct AssetBake {
  std::vector<OutputFile> files;  // every output but report.json and manifest.json, in write order
  nlohmann::json manifest;        // what runtimes read; identical for identical input and settings
  nlohmann::json report;          // settings, counts, stage times and memory, warnings
  std::string page;               // report.html (AssetOptions::report_page); empty when not asked for
  BakeResult result;              // the bake's figures (level .glb bytes moved into `files`)
  SampleStats sampled;            // backend empty for point-set inputs
  ReadReport read;
  // The GL driver the outputs were measured with, {renderer, version} (GL_RENDERER, GL_VERSION;
  // null when not measured): in report.json and on the page, never in the manifest, which is
  // byte-identical for the same input and settings on any machine while the driver's name is not.
  nlohmann::json gl;
};

// Reads `path` as a point set; a mesh is sampled by depth peeling (its figures in `sampled`, the
// mesh itself in `mesh`, when given; sampled->backend stays empty for point sets). Throws the
// readers' InputErrors, and InputError `<command>.empty` for a set without points.
PointSet load_point_set(const std::string& path, const ReadOptions& read, const SampleOptions& sample,
                        const std::string& command, ReadReport& report, SampleStats* sampled = nullptr,
                        TriangleMesh* mesh = nullptr, std::vector<std::uint32_t>* triangles = nullptr);

// The same for a model already read (`path` names it in errors).
PointSet points_of(Model model, const std::string& path, const ReadOptions& read, const SampleOptions& sample, const std::string& command,
                   ReadReport& report, SampleStats* sampled = nullptr, TriangleMesh* mesh = nullptr,
                   std::vector<std::uint32_t>* triangles = nullptr);

// Bakes one asset. `input_name` is how the manifest and report name the input (the path as the
// user wrote it); output files are named after its stem.
AssetBake bake_asset(const std::string& path, const AssetOptions& options, const std::string& input_name);

// The cluster levels' default cell widths: bounding-box diagonal / 128, 64, 32, 16, 8.
std::vector<double> default_cluster_cells(const TriangleMesh& mesh);

// The simplify levels' default triangle budgets: the input's triangles / 4, 16, 64, 256, 1024,
// those of at least 16 triangles.
std::vector<std::size_t> default_simplify_budgets(const TriangleMesh& mesh);

// Edge-collapse LODs of `mesh` as files STEM_S<i>.glb, appended to `files`: normals the mesh's own
// where it has them (kept through the simplifier), else smooth ones when `smooth`, else none (flat);
// a mesh with materials keeps them and its textures, others get the LOD material. A budget whose
// LOD is the same mesh as the last one written is skipped, and where the simplifier stalls (stays
// above its budget) the smaller budgets are not tried. Returns {"levels": the written LODs' manifest
// entries (file, target and kept triangles, vertices, bytes, error and the largest on-screen size of
// the object at which that error stays under half a pixel, as the impostor levels give it),
// "skipped": [{target_triangles, skipped: why}] and "stopped": why, where there are any}. Shared by
// the bake and `qf-bake simplify`. UsageError for a budget that leaves no triangle. A textured
// LOD's textures are PNG, or KTX2 where `gltf` asks for it (--textures ktx2: the impostor levels'
// encoder and codecs), their entry then with texture_bytes and gpu_bytes as a level's.
nlohmann::json simplify_level_files(const TriangleMesh& mesh, const std::vector<std::size_t>& budgets, const std::string& stem,
                                    std::vector<OutputFile>& files, bool smooth = true,
                                    SimplifyMethod method = SimplifyMethod::kCollapse, const GltfOptions& gltf = {});

// The cluster LODs' switching rule (seed 002): a level serves while its cell is at most this many
// pixels wide on screen, so an object of diagonal D gets max_screen_pixels = kClusterCellPixels x
// D / cell_width.
constexpr double kClusterCellPixels = 5;

// Cluster levels as files STEM_C<i>.glb (and STEM_C<i>.draco.glb with `draco`), appended to
// `files`; returns their manifest entries (with max_screen_pixels for an object of `diagonal`).
nlohmann::json cluster_level_files(const std::vector<LodMesh>& lods, const std::string& stem, bool draco,
                                   std::vector<OutputFile>& files, double diagonal);

// The manifest.json in `folder` (null when there is none or it does not parse), and the files it
// lists under "files" (see write_asset); `present` says whether all of them are in the folder with
// their listed sizes.
nlohmann::json read_asset_manifest(const std::string& folder);
std::vector<std::string> listed_files(const nlohmann::json& manifest);
bool listed_files_present(const std::string& folder, const nlohmann::json& manifest);

// What a bake's files weigh, from its manifest.json: `written`, every file its "files" lists (all
// but the reports); `chain`, the files its recommended chain ships (each once; the input itself,
// which the chain starts at, and STEM_lods.glb, the same files combined, aside). A point impostor or
// a mesh LOD no band takes is written and not shipped. No chain (not measured, --no-chain): absent.
struct OutputBytes {
  std::uintmax_t written = 0;
  std::optional<std::uintmax_t> chain;
};
OutputBytes output_bytes(const nlohmann::json& manifest);
// The same of a bake not yet written: its `files` in place of the manifest's list.
OutputBytes output_bytes(const nlohmann::json& manifest, const std::vector<OutputFile>& files);

// Writes `files`, `report` (report.json, when not null), `page` (report.html, when not empty) and
// `manifest` (manifest.json, given a "files" list: name and size of every file above but the
// reports) as the new content of `out`, replacing the folder whole (core/output_folder.h): at every
// instant it is the old bake or the new one. Of the old folder, what its manifest listed and its
// reports are dropped; anything else (files a user put there) is carried into the new one.
void write_asset(OutputFolder& out, const std::vector<OutputFile>& files, nlohmann::json manifest, const nlohmann::json& report,
                 const std::string& page = "");

}  // namespace qf
