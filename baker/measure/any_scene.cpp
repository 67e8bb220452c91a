// Loading any drawable file, and the paired renders of the fidelity metrics.
#include "measure/any_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/neighborhoods.h"
#include "core/error.h"
#include "core/file_io.h"
#include "io/model_io.h"
#include "measure/reference_scene.h"

namespace qf::render {

Bounds AnyScene::bounds() const {
  return kind == kImpostor  ? impostor.bounds
         : kind == kSplats  ? splats.bounds
         : kind == kPoints  ? points.bounds
         : kind == kCluster ? cluster.bounds
                            : mesh.bounds;
}

std::string AnyScene::describe() const {
  if (kind == kImpostor) return std::to_string(impostor.items.size()) + " quads";
  if (kind == kPoints) return std::to_string(points.positions.size()) + " impostor points";
  if (kind == kCluster)
    return std::to_string(cluster.mesh.indices.size() / 3) + " triangles, " + std::to_string(cluster.thickness.size()) +
           " thick edges, " + std::to_string(cluster.points.size()) + " points";
  if (kind == kSplats) return std::to_string(splats.positions.size()) + " points";
  return std::to_string(mesh.indices.size() / 3) + " triangles";
}

void AnyScene::attach(Renderer& r) const {
  if (kind == kImpostor) r.set_scene(impostor);
  else if (kind == kPoints) r.set_scene(points, fade_mesh ? &*fade_mesh : nullptr);
  else if (kind == kCluster) r.set_scene(cluster);
  else if (kind == kSplats) r.set_scene(splats);
  else r.set_scene(mesh);
  r.set_engine_scene(engine);
}

namespace {

AnyScene from_baked(BakedScene b) {
  AnyScene s;
  s.kind = b.kind == BakedScene::kPoints ? AnyScene::kPoints : b.kind == BakedScene::kCluster ? AnyScene::kCluster : AnyScene::kImpostor;
  s.impostor = std::move(b.impostor);
  s.points = std::move(b.points);
  s.cluster = std::move(b.cluster);
  s.engine = std::move(b.engine);
  s.asset = b.asset;
  s.lods = std::move(b.lods);
  s.lod_coverage = std::move(b.lod_coverage);
  return s;
}

}  // namespace

AnyScene load_scene(const std::vector<std::uint8_t>& glb, const std::string& name) { return from_baked(load_baked(glb, name)); }

AnyScene load_scene(const std::string& path, const ReadOptions& read) {
  const std::string ext = file_extension(path);
  if (ext == "glb" || ext == "gltf") return from_baked(load_baked(path));
  return load_input(path, read);
}

AnyScene load_input(const std::string& path, const ReadOptions& read) {
  AnyScene s;
  Model m = read_model(path, read);
  if (m.is_mesh) {
    s.kind = AnyScene::kMesh;
    s.mesh = mesh_scene(m.mesh, path);
    s.engine = engine_scene(m.mesh, s.mesh);
    // A mesh with materials (OBJ + MTL) is an asset as a glTF one is: its look is the engine's.
    s.asset = has_material_look(m.mesh);
  } else {
    s.kind = AnyScene::kSplats;
    // The bake's loader drops the same outliers (pipeline/asset.cpp load_point_set).
    OutlierOptions outliers;
    outliers.factor = read.outlier_factor;
    if (read.outlier_factor > 0) drop_outliers(m.points, outliers);
    s.splats = splat_scene(std::move(m.points), path);
    s.engine = engine_scene(s.splats);
  }
  return s;
}

void AnyScene::select_lod(int i) {
  if (lods.empty() && i == 0) return;
  if (i < 0 || i >= static_cast<int>(lods.size()))
    throw UsageError("--lod " + std::to_string(i) + ": the file has " + std::to_string(std::max<std::size_t>(1, lods.size())) + " level(s)");
  lod = i;
  impostor = lods[static_cast<std::size_t>(i)].impostor;
  engine = lods[static_cast<std::size_t>(i)].engine;
}

int AnyScene::lod_for_coverage(double coverage) const {
  for (std::size_t i = 0; i < lods.size() && i < lod_coverage.size(); ++i)
    if (coverage >= lod_coverage[i]) return static_cast<int>(i);
  return lods.empty() ? 0 : static_cast<int>(lods.size()) - 1;
}

ViewMetrics mean_of(const std::vector<ViewMetrics>& v) {
  // Each figure is the mean over the views that have evidence for it (NaN where none has);
  // coverage is the views' summed coverages' ratio, so a view that shows a sliver weighs little.
  ViewMetrics m;
  m.iou = m.soft_iou = m.coverage = 0;
  double n_psnr = 0, n_iou = 0;
  for (const ViewMetrics& x : v) {
    if (!std::isnan(x.psnr)) m.psnr += x.psnr, m.soft_iou += x.soft_iou, m.mae += x.mae, ++n_psnr;
    if (!std::isnan(x.iou)) m.iou += x.iou, ++n_iou;
    m.covered_reference += x.covered_reference, m.covered_image += x.covered_image;
    m.holes += x.holes, m.see_through += x.see_through, m.brightness += x.brightness, m.reference_brightness += x.reference_brightness;
    m.covered += x.covered;
  }
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  const double n = static_cast<double>(std::max<std::size_t>(1, v.size()));
  m.psnr = n_psnr > 0 ? m.psnr / n_psnr : kNone, m.soft_iou = n_psnr > 0 ? m.soft_iou / n_psnr : kNone, m.mae = n_psnr > 0 ? m.mae / n_psnr : 0;
  m.iou = n_iou > 0 ? m.iou / n_iou : kNone;
  m.coverage = has_evidence(m) ? m.covered_image / m.covered_reference : kNone;
  m.covered = static_cast<std::size_t>(static_cast<double>(m.covered) / n);
  m.covered_reference /= n, m.covered_image /= n;
  m.holes /= n, m.see_through /= n, m.brightness /= n, m.reference_brightness /= n;
  return m;
}

RenderPair render_pair(Renderer& r, const Camera& c, DrawSettings s) {
  RenderPair p;
  s.background = {0, 0, 0};
  if (s.method == Method::kEngine) {
    // One frame: its alpha is the coverage A, and a frame over white is the one over black plus
    // (1 - A) x 255 (exact for the engine's blend; half the drawing of the bake's measuring).
    s.coverage_alpha = true;
    r.draw(c, s);
    p.over_black = r.read_pixels();
    p.over_white = p.over_black;
    for (std::size_t i = 0; i < p.over_white.rgba.size(); i += 4) {
      const int open = 255 - p.over_white.rgba[i + 3];
      for (std::size_t k = 0; k < 3; ++k) p.over_white.rgba[i + k] = static_cast<std::uint8_t>(std::min(255, p.over_white.rgba[i + k] + open));
      p.over_black.rgba[i + 3] = p.over_white.rgba[i + 3] = 255;
    }
    return p;
  }
  r.draw(c, s);
  p.over_black = r.read_pixels();
  s.background = {255, 255, 255};
  r.draw(c, s);
  p.over_white = r.read_pixels();
  return p;
}

}  // namespace qf::render
