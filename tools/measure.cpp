// The measuring library: candidates and the input's truth drawn per size and view, scored.
#include "tools/measure.h"

#include <algorithm>
#include <memory>
#include <limits>
#include <stdexcept>

#include "core/error.h"
#include "core/file_io.h"
#include "core/progress.h"
#include "gl/egl.h"
#include "pipeline/chain.h"
#include "runtime_gl/camera.h"
#include "tools/any_scene.h"

namespace qf::render {
namespace {

DrawSettings engine_settings() {
  DrawSettings s;
  s.method = Method::kEngine;
  s.background = {128, 128, 128};  // colours compared over grey, as qf-render eval
  return s;
}

Scores scores_of(const ViewMetrics& m) { return {m.psnr, m.iou, m.soft_iou, true}; }

// One on-screen size: its cameras and the truth from each.
struct SizeViews {
  int size = 0;
  std::vector<Camera> cams;
  std::vector<RenderPair> truth;
};

// 1. The truth at every size and view: the input drawn once per view at the truth's side (`truth`
// x the largest size) and box-filtered down to each size. One drawing for all sizes is cheaper,
// and truer at small sizes: drawn at 8 x 16 px, the generated tree's alpha-tested leaves vanish
// in its own mipmaps (its level of 25 quads at 16 px scored 17.3 dB, IoU 0.58 against that
// truth; 12.2 dB, IoU 0.07 against 4 x 16 px).
std::vector<SizeViews> truth_views(const AnyScene& input, const Sphere& sphere, const MeasureOptions& o) {
  const int side = truth_side(o.sizes, o.truth);
  Renderer renderer(side, side);
  renderer.set_engine_only(input.engine);
  std::vector<SizeViews> out;
  for (int size : o.sizes) out.push_back({size, {}, {}});
  for (int v = 0; v < o.views; ++v) {
    const Vec3f d = sphere_direction(v, o.views);
    const RenderPair p = render_pair(renderer, orbit_camera(sphere, d, 0, side, side), engine_settings());
    for (SizeViews& s : out) {
      const int factor = side / s.size;
      s.cams.push_back(orbit_camera(sphere, d, 0, s.size, s.size));
      s.truth.push_back(factor > 1 ? RenderPair{box_downsample(p.over_black, factor), box_downsample(p.over_white, factor)} : p);
    }
  }
  return out;
}

// 2. A scene attached to `renderer`, drawn at every size up to `largest` pixels from the truth's
// views, scored per view and averaged per size.
std::vector<Scores> scores_at_sizes(Renderer& renderer, const std::vector<SizeViews>& sizes, double largest) {
  std::vector<Scores> out;
  for (const SizeViews& s : sizes) {
    if (s.size > largest) {
      out.push_back(Scores{0, 0, 0, false});
      continue;
    }
    renderer.resize(s.size, s.size);
    std::vector<ViewMetrics> per_view;
    for (std::size_t v = 0; v < s.cams.size(); ++v)
      per_view.push_back(compare_renders(s.truth[v], render_pair(renderer, s.cams[v], engine_settings()), engine_settings().background));
    out.push_back(scores_of(mean_of(per_view)));
  }
  return out;
}

}  // namespace

// The input as the truth: a glTF file as its file says (the loader, as qf-render eval draws it),
// others, and glTF files the loader does not take (Draco-compressed: runtime_gl decodes no
// Draco), as the baker's readers read them.
AnyScene measured_input(const std::string& path, const ReadOptions& read) {
  const std::string ext = file_extension(path);
  if (ext == "glb" || ext == "gltf") {
    try {
      return load_scene(path);
    } catch (const InputError&) {
      // The bake read it, so its reader can.
    }
  }
  return load_input(path, read);
}

int truth_factor(int size, int truth) { return std::max(1, std::min(truth, kMaxTruthSide / std::max(1, size))); }

int truth_side(const std::vector<int>& sizes, int truth) {
  const int largest = *std::max_element(sizes.begin(), sizes.end());
  const int side = largest * truth_factor(largest, truth);
  for (int s : sizes)
    if (s < 1 || side % s != 0) throw UsageError("measuring: size " + std::to_string(s) + " does not divide the truth's side " + std::to_string(side));
  return side;
}

Measurements measure_files(const std::string& input_path, const std::vector<Candidate>& candidates, const MeasureOptions& o) {
  Measurements m{o.sizes, o.views, o.truth, {}};
  if (o.sizes.empty() || o.views < 1) return m;
  std::unique_ptr<HeadlessContext> context;
  try {
    context = std::make_unique<HeadlessContext>();
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("measuring the outputs draws them, which needs an EGL/OpenGL driver (or --no-measure): ") + e.what());
  }
  progress::step("measuring: drawing the input's reference views");
  const AnyScene input = measured_input(input_path, o.read);
  const Sphere sphere = bounding_sphere(input.bounds());
  const std::vector<SizeViews> sizes = truth_views(input, sphere, o);
  // 3. Every candidate, loaded and uploaded once (only what the engine method draws), drawn where
  // it can be chosen.
  Renderer renderer(1, 1);
  progress::step("measuring the outputs as an engine draws them", candidates.size());
  for (const Candidate& c : candidates) {
    const AnyScene scene = load_scene(*c.bytes, c.file);
    renderer.set_engine_only(scene.engine);
    const double largest = c.max_pixels > 0 ? kShownAbove * c.max_pixels : std::numeric_limits<double>::infinity();
    m.files.push_back({c.file, c.kind, c.bytes->size(), scores_at_sizes(renderer, sizes, largest)});
    progress::advance();
  }
  return m;
}

}  // namespace qf::render
