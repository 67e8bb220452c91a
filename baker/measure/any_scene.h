// Whatever file qf-render or qf-diff is given, loaded ready to draw (a baked .glb of any kind, a
// point set as splats, a mesh), and the paired renders over black and white the fidelity metrics
// are computed from (image_ops compare_renders).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/model_io.h"
#include "runtime_gl/draw_gl11.h"
#include "measure/image_metrics.h"
#include "runtime_gl/loader.h"

namespace qf::render {

struct AnyScene {
  enum Kind { kImpostor, kSplats, kMesh, kPoints, kCluster } kind = kImpostor;
  // An input's own look, which only the engine method draws: a glTF file the baker did not write (no
  // QF extension), or a mesh with materials (kMesh, e.g. OBJ + MTL; the GL 1.1 methods draw it
  // without them).
  bool asset = false;
  ClusterScene cluster;
  ImpostorScene impostor;
  SplatScene splats;
  MeshScene mesh;
  PointImpostorScene points;
  EngineScene engine;                 // the same, as a standard engine draws it (Method::kEngine)
  std::optional<MeshScene> fade_mesh;  // kPoints: the mesh it fades to when near (--mesh)
  // A combined LOD file: its levels (finest first) and their screen coverages; the fields above
  // hold the selected one (select_lod), the finest when loaded.
  std::vector<BakedScene> lods;
  std::vector<double> lod_coverage;
  int lod = 0;
  void select_lod(int i);  // UsageError when out of range
  // The level an engine shows when the object's bounding sphere spans `coverage` of the screen
  // height: the first whose MSFT_screencoverage it reaches (the coarsest below them all).
  int lod_for_coverage(double coverage) const;
  Bounds bounds() const;
  std::string describe() const;      // e.g. "273 quads", "37705 points"
  void attach(Renderer& r) const;    // makes it (and its engine view) the renderer's scene
};

// By extension: .glb/.gltf through load_baked, anything else through the model readers (with
// `read`). Throws InputError naming the file.
AnyScene load_scene(const std::string& path, const ReadOptions& read = {});
// An input file as the baker's readers read it (any format they take, glTF assets with their
// materials too): a mesh, else a point set as splats.
AnyScene load_input(const std::string& path, const ReadOptions& read = {});
// A .glb file's bytes in memory, as load_scene reads the file; errors name `name`.
AnyScene load_scene(const std::vector<std::uint8_t>& glb, const std::string& name);

// The scene drawn from `c` over black and over white (coverage = 1 - (W - B) / 255): by the
// engine method one frame with its coverage in alpha, by the others two frames.
RenderPair render_pair(Renderer& r, const Camera& c, DrawSettings s);

// The mean of each metric over views.
ViewMetrics mean_of(const std::vector<ViewMetrics>& v);

}  // namespace qf::render
