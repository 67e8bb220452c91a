// The analysis recipe (method.md stages 1-3): named, timed steps.
#include "analysis/analysis.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace qf {
namespace {

class StepTimer {
 public:
  explicit StepTimer(std::vector<StepTime>& out) : out_(out) {}
  template <class F>
  auto run(const char* name, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    auto result = f();
    out_.push_back({name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
    return result;
  }

 private:
  std::vector<StepTime>& out_;
};

// Frees a per-point array now (clear() would keep its capacity).
template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

}  // namespace

SurfaceAnalysis analyze_surface(const PointSet& points, const AnalysisOptions& options, AnalysisKeep keep) {
  const bool lean = keep == AnalysisKeep::kStiffnessAndNormals;
  SurfaceAnalysis a;
  AnalysisReport& r = a.report;
  r.points = points.size();
  StepTimer timer(r.times);
  // 1. Neighbourhoods (paper 2.1).
  a.neighborhoods = timer.run("neighbourhoods", [&] {
    return compute_neighborhoods(points.positions, options.neighborhoods, &r.neighborhoods);
  });
  // 2. Moments and frames, then consistently oriented normals (serial where the input has none).
  a.frames = timer.run("frames", [&] { return compute_local_frames(points.positions, a.neighborhoods); });
  timer.run("orientation", [&] {
    orient_normals(points.positions, a.neighborhoods, points.has_normals() ? &points.normals : nullptr, a.frames);
    return 0;
  });
  r.normals_flipped = a.frames.flipped;
  r.normal_components = a.frames.components;
  r.isolated = a.frames.isolated;
  // 3. Surface classifier (eq. 3) and surface variation.
  a.classifier = timer.run("classifier", [&] { return classify(a.frames, a.neighborhoods, options.classifier); });
  // 4. Local Delaunay fans (paper 2.2).
  a.fans = timer.run("fans", [&] { return compute_fans(points.positions, a.neighborhoods, a.frames, &r.fans); });
  r.mean_fan_size = points.size() ? double(a.fans.triangles.size()) / double(points.size()) : 0.0;
  if (lean) {
    // The stiffness matrix reads only the fans and the classifier value.
    release(a.neighborhoods.offsets), release(a.neighborhoods.indices), release(a.neighborhoods.distances);
    release(a.frames.eigenvalues), release(a.frames.e0), release(a.frames.e1);
    release(a.frames.centroid_offset), release(a.frames.radius), release(a.classifier.variation);
  }
  // 5. Stiffness matrix (eqs. 5-7).
  a.stiffness = timer.run("stiffness", [&] {
    return assemble_stiffness(points.positions, a.fans, a.classifier.value, &r.stiffness);
  });
  r.nonzeros = static_cast<std::size_t>(a.stiffness.nonZeros());
  if (lean) release(a.fans.offsets), release(a.fans.triangles), release(a.classifier.value);
  return a;
}

Rgb8 classifier_color(float c, const ClassifierOptions& options) {
  // Red at C = 1/alpha (flat), blue two decades lower and below: where the paper's creases are.
  const double hi = 1.0 / options.alpha, lo = hi / 100.0;
  double t = (std::log(std::max<double>(c, lo)) - std::log(lo)) / (std::log(hi) - std::log(lo));
  t = std::clamp(t, 0.0, 1.0);
  // Piecewise-linear rainbow: blue (0) -> cyan -> green -> yellow -> red (1).
  static const double stops[5][3] = {{0, 0, 255}, {0, 255, 255}, {0, 200, 0}, {255, 230, 0}, {230, 0, 0}};
  const double x = t * 4;
  const int k = std::min(3, static_cast<int>(x));
  const double f = x - k;
  auto mix = [&](int ch) { return static_cast<std::uint8_t>(std::lround(stops[k][ch] + f * (stops[k + 1][ch] - stops[k][ch]))); };
  return {mix(0), mix(1), mix(2)};
}

}  // namespace qf
