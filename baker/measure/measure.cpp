// The measuring library: candidates and the input's truth drawn per size and view, scored.
#include "measure/measure.h"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "core/error.h"
#include "core/file_io.h"
#include "core/progress.h"
#include "gl/egl.h"
#include "measure/screen_sizes.h"
#include "runtime_gl/camera.h"
#include "measure/any_scene.h"

namespace qf::render {
namespace {

DrawSettings engine_settings() {
  DrawSettings s;
  s.method = Method::kEngine;
  s.background = {128, 128, 128};  // colours compared over grey, as qf-render eval
  return s;
}

Scores scores_of(const ViewMetrics& m) { return {m.psnr, m.iou, m.soft_iou, m.coverage, true}; }

// One on-screen size: its cameras and the truth from each.
struct SizeViews {
  int size = 0;
  std::vector<Camera> cams;
  std::vector<RenderPair> truth;
};

// 1. The truth at `sizes` from every view: the input drawn once per view at the truth's side
// (`truth` x the largest of them) and box-filtered down to each. One drawing for all sizes is
// cheaper, and truer at small sizes: drawn at 8 x 16 px, the generated tree's alpha-tested leaves
// vanish in its own mipmaps (its level of 25 quads at 16 px scored 17.3 dB, IoU 0.58 against that
// truth; 12.2 dB, IoU 0.07 against 4 x 16 px).
std::vector<SizeViews> truth_views(const AnyScene& input, const Sphere& sphere, const std::vector<int>& sizes, const MeasureOptions& o) {
  const int side = truth_side(sizes, o.truth);
  Renderer renderer(side, side);
  renderer.set_engine_only(input.engine);
  std::vector<SizeViews> out;
  for (int size : sizes) out.push_back({size, {}, {}});
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

// 2. A scene attached to `renderer`, drawn at one size from the truth's views, scored per view and
// averaged.
Scores scores_at(Renderer& renderer, const SizeViews& s) {
  renderer.resize(s.size, s.size);
  std::vector<ViewMetrics> per_view;
  for (std::size_t v = 0; v < s.cams.size(); ++v)
    per_view.push_back(compare_renders(s.truth[v], render_pair(renderer, s.cams[v], engine_settings()), engine_settings().background));
  return scores_of(mean_of(per_view));
}

std::vector<Scores> scores_at_sizes(Renderer& renderer, const std::vector<SizeViews>& sizes) {
  std::vector<Scores> out;
  for (const SizeViews& s : sizes) out.push_back(scores_at(renderer, s));
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

Measurements measure_files(const std::string& input_path, const std::vector<Candidate>& candidates, const HoldBar& bar, const MeasureOptions& o) {
  Measurements m{o.sizes, o.views, o.truth, {}, {}, {}, {}};
  if (o.sizes.empty() || o.views < 1) return m;
  std::unique_ptr<HeadlessContext> context;
  try {
    context = std::make_unique<HeadlessContext>();
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("measuring the outputs draws them, which needs an EGL/OpenGL driver (or --no-measure): ") + e.what());
  }
  m.gl_renderer = context->renderer();
  m.gl_version = context->version();
  progress::step("measuring: drawing the input's reference views");
  const AnyScene input = measured_input(input_path, o.read);
  const Sphere sphere = bounding_sphere(input.bounds());
  const std::vector<SizeViews> sizes = truth_views(input, sphere, o.sizes, o);
  // 3. The asset itself at each size, as an engine shows it (its own mipmaps, alpha test): every
  // file is judged relative to it. Then every candidate, loaded and uploaded once (only what the
  // engine method draws), drawn at every size: its figures decide where it holds.
  Renderer renderer(1, 1);
  renderer.set_engine_only(input.engine);
  m.asset = {input_path, "asset", 0, scores_at_sizes(renderer, sizes)};
  progress::step("measuring the outputs as an engine draws them", candidates.size());
  std::vector<AnyScene> scenes;
  for (const Candidate& c : candidates) {
    scenes.push_back(load_scene(*c.bytes, c.file));
    renderer.set_engine_only(scenes.back().engine);
    m.files.push_back({c.file, c.kind, c.bytes->size(), scores_at_sizes(renderer, sizes)});
    progress::advance();
  }
  // 4. Larger sizes, doubling up to `largest`, while a file holds at the largest measured so far:
  // only those files are drawn there (the others could be chosen at no larger size), beside the
  // asset, against a truth of its own. Measuring every file at 512 and 1024 px took bunny00's
  // bake 2.5x the time, and none of its files held above 256 px.
  for (int size = o.sizes.front() * 2; size <= o.largest; size *= 2) {
    std::vector<bool> held(m.files.size());
    bool any = false;
    for (std::size_t i = 0; i < m.files.size(); ++i) {
      held[i] = holds(m.files[i].at_size.front(), m.asset.at_size.front(), bar);
      any = any || held[i];
    }
    if (!any) break;
    progress::step("measuring at " + std::to_string(size) + " px the files that hold at " + std::to_string(size / 2));
    const SizeViews s = truth_views(input, sphere, {size}, o).front();
    m.sizes.insert(m.sizes.begin(), size);
    renderer.set_engine_only(input.engine);
    m.asset.at_size.insert(m.asset.at_size.begin(), scores_at(renderer, s));
    for (std::size_t i = 0; i < m.files.size(); ++i) {
      Scores at{0, 0, 0, 0, false};
      if (held[i]) renderer.set_engine_only(scenes[i].engine), at = scores_at(renderer, s);
      m.files[i].at_size.insert(m.files[i].at_size.begin(), at);
    }
  }
  return m;
}

}  // namespace qf::render
