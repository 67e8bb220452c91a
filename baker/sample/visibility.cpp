// Visibility of sampled points from outside views (visibility.h): a CPU depth buffer per view
// direction, the points tested against it.
#include "sample/visibility.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel_errors.h"

namespace qf {
namespace {

constexpr float kEmpty = std::numeric_limits<float>::infinity();

// One orthographic view: looking along -direction from outside the bounding sphere; image x along
// e1, y along e2; depth grows away from the viewer, 0 at the sphere's near pole.
struct View {
  Vec3f direction, e1, e2;
};

View fibonacci_view(int i, int n) {
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * i;
  View v;
  v.direction = {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)), static_cast<float>(z)};
  const Vec3f helper = std::fabs(v.direction.z) < 0.9f ? Vec3f{0, 0, 1} : Vec3f{1, 0, 0};
  v.e1 = normalized(cross(helper, v.direction));
  v.e2 = cross(v.direction, v.e1);
  return v;
}

struct Frame {
  Vec3f center;
  float radius = 0, pixel = 0;
  int size = 0;
  // Image coordinates: pixel (i, j) has its centre at (i, j).
  double x(const View& v, Vec3f p) const { return (dot(p - center, v.e1) + radius) / pixel - 0.5; }
  double y(const View& v, Vec3f p) const { return (dot(p - center, v.e2) + radius) / pixel - 0.5; }
  double depth(const View& v, Vec3f p) const { return radius - dot(p - center, v.direction); }
};

// v as an int within [lo, hi] (v may be far outside int's range: a triangle reaching far past the grid).
int clamped(double v, int lo, int hi) { return static_cast<int>(std::clamp(v, double(lo), double(hi))); }

bool occludes(const TriangleMesh& mesh, std::size_t t) {
  if (mesh.triangle_materials.empty()) return true;
  return mesh.materials[mesh.triangle_materials[t]].alpha_mode == AlphaMode::kOpaque;
}

// The nearest depth of the opaque triangles per pixel (kEmpty where none).
std::vector<float> depth_buffer(const TriangleMesh& mesh, const Frame& f, const View& v) {
  const int n = f.size;
  std::vector<float> z(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), kEmpty);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!occludes(mesh, t)) continue;
    double x[3], y[3], d[3];
    for (int c = 0; c < 3; ++c) {
      const Vec3f p = mesh.positions[mesh.triangles[t][static_cast<std::size_t>(c)]];
      x[c] = f.x(v, p), y[c] = f.y(v, p), d[c] = f.depth(v, p);
    }
    const double area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (!(std::fabs(area) > 0)) continue;
    const int i0 = clamped(std::ceil(std::min({x[0], x[1], x[2]})), 0, n);
    const int i1 = clamped(std::floor(std::max({x[0], x[1], x[2]})), -1, n - 1);
    const int j0 = clamped(std::ceil(std::min({y[0], y[1], y[2]})), 0, n);
    const int j1 = clamped(std::floor(std::max({y[0], y[1], y[2]})), -1, n - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        // Barycentric weights of the pixel centre; a centre on an edge counts for both triangles
        // (a depth buffer takes the nearer, so no crack and no double count can arise).
        const double w1 = ((i - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (j - y[0])) / area;
        const double w2 = ((x[1] - x[0]) * (j - y[0]) - (i - x[0]) * (y[1] - y[0])) / area;
        const double w0 = 1 - w1 - w2;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        float& slot = z[static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i)];
        slot = std::min(slot, static_cast<float>(w0 * d[0] + w1 * d[1] + w2 * d[2]));
      }
  }
  return z;
}

// Whether point p is within `tolerance` of the farthest nearest depth in its 3 x 3 pixels (an
// empty pixel there, or one outside the image, makes it seen: it lies on a silhouette).
bool seen(const std::vector<float>& z, const Frame& f, const View& v, Vec3f p, double tolerance) {
  const int ci = clamped(std::round(f.x(v, p)), -2, f.size + 1), cj = clamped(std::round(f.y(v, p)), -2, f.size + 1);
  float farthest = 0;
  for (int j = cj - 1; j <= cj + 1; ++j)
    for (int i = ci - 1; i <= ci + 1; ++i) {
      if (i < 0 || j < 0 || i >= f.size || j >= f.size) return true;
      farthest = std::max(farthest, z[static_cast<std::size_t>(j) * static_cast<std::size_t>(f.size) + static_cast<std::size_t>(i)]);
    }
  return f.depth(v, p) <= double(farthest) + tolerance;
}

}  // namespace

std::vector<char> visible_points(const TriangleMesh& mesh, const std::vector<Vec3f>& positions, float pixel,
                                 const VisibilityOptions& o) {
  std::vector<char> visible(positions.size(), o.views <= 0 ? 1 : 0);
  if (o.views <= 0 || positions.empty()) return visible;
  // 1. The views' common frame: the bounding sphere of the mesh and the points.
  Bounds b = mesh.bounds();
  for (const Vec3f& p : positions) b.add(p);
  Frame f;
  f.center = b.center();
  f.radius = std::max(0.5f * b.diagonal(), 1e-30f);
  f.size = clamped(std::ceil(2.0 * f.radius / std::max(pixel, 1e-30f)), 16, std::max(16, o.max_resolution));
  f.pixel = 2 * f.radius / static_cast<float>(f.size);
  const double tolerance = std::max(double(pixel), double(f.pixel));
  // 2. Views in batches (their depth buffers drawn side by side), the points not yet seen tested
  //    against each batch: memory for a batch's buffers only, and most points are seen early.
  constexpr int kBatch = 4;
  for (int first = 0; first < o.views; first += kBatch) {
    const int count = std::min(kBatch, o.views - first);
    std::vector<View> views(static_cast<std::size_t>(count));
    std::vector<std::vector<float>> depth(static_cast<std::size_t>(count));
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < count; ++k)
      errors.run(k, [&] {
        views[static_cast<std::size_t>(k)] = fibonacci_view(first + k, o.views);
        depth[static_cast<std::size_t>(k)] = depth_buffer(mesh, f, views[static_cast<std::size_t>(k)]);
      });
    errors.rethrow();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(positions.size()); ++i) {
      char& v = visible[static_cast<std::size_t>(i)];
      for (int k = 0; k < count && !v; ++k)
        v = seen(depth[static_cast<std::size_t>(k)], f, views[static_cast<std::size_t>(k)], positions[static_cast<std::size_t>(i)], tolerance);
    }
  }
  return visible;
}

}  // namespace qf
