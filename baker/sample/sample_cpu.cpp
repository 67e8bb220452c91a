// The CPU reference of the depth peeling (sample.h): every triangle rasterised at pixel centres
// with a top-left rule on each axis' grid, fragments sorted per pixel by depth. The result is the
// GL backend's layered depth images, computed without GL.
#include <algorithm>
#include <cmath>

#include "core/parallel_errors.h"
#include "sample/sample.h"

namespace qf {
namespace {

struct Fragment {
  std::uint32_t pixel;
  double depth;
  std::uint32_t triangle;
};

// Shared edges are covered once: a pixel centre exactly on an edge belongs to the triangle on
// whose side the edge runs "down", or "right" when horizontal (for counter-clockwise triangles).
// The same rule for d and -d always disagrees, so two triangles sharing an edge never both take it.
bool owns_edge(double dx, double dy) { return dy < 0 || (dy == 0 && dx > 0); }

// Fragments of one triangle on one axis' grid, in pixel units (pixel (i, j) centre at (i, j)).
void rasterize(const std::array<double, 3>& x, const std::array<double, 3>& y, const std::array<double, 3>& z,
               std::uint32_t triangle, int width, int height, std::vector<Fragment>& out) {
  int a = 0, b = 1, c = 2;
  double area = (x[b] - x[a]) * (y[c] - y[a]) - (y[b] - y[a]) * (x[c] - x[a]);
  if (area == 0) return;  // seen edge-on: no fragments, as in GL
  if (area < 0) std::swap(b, c), area = -area;
  const int i0 = std::max(0, static_cast<int>(std::ceil(std::min({x[0], x[1], x[2]}))));
  const int i1 = std::min(width - 1, static_cast<int>(std::floor(std::max({x[0], x[1], x[2]}))));
  const int j0 = std::max(0, static_cast<int>(std::ceil(std::min({y[0], y[1], y[2]}))));
  const int j1 = std::min(height - 1, static_cast<int>(std::floor(std::max({y[0], y[1], y[2]}))));
  const int order[3][2] = {{b, c}, {c, a}, {a, b}};  // edge opposite vertex a, b, c
  const int opposite[3] = {a, b, c};
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      double w[3];
      bool inside = true;
      for (int e = 0; e < 3 && inside; ++e) {
        const int p = order[e][0], q = order[e][1];
        const double dx = x[q] - x[p], dy = y[q] - y[p];
        w[e] = dx * (j - y[p]) - dy * (i - x[p]);
        inside = w[e] > 0 || (w[e] == 0 && owns_edge(dx, dy));
      }
      if (!inside) continue;
      double depth = 0;
      for (int e = 0; e < 3; ++e) depth += w[e] / area * z[opposite[e]];
      out.push_back({static_cast<std::uint32_t>(j) * static_cast<std::uint32_t>(width) + static_cast<std::uint32_t>(i), depth,
                     triangle});
    }
}

AxisLayers peel_axis(const TriangleMesh& mesh, const SampleGrid& grid, const SampleOptions& options, int axis) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  AxisLayers L = empty_layers(grid, axis);
  // 1. Every fragment of every triangle drawn on this axis.
  std::vector<Fragment> frags;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (options.per_axis_triangles && sampling_axis(mesh, t) != axis) continue;
    std::array<double, 3> x{}, y{}, z{};
    for (int k = 0; k < 3; ++k) {
      const Vec3f& p = mesh.positions[mesh.triangles[t][static_cast<std::size_t>(k)]];
      x[static_cast<std::size_t>(k)] = (double(p[u]) - grid.origin[u]) / grid.pixel - 0.5;
      y[static_cast<std::size_t>(k)] = (double(p[v]) - grid.origin[v]) / grid.pixel - 0.5;
      z[static_cast<std::size_t>(k)] = p[axis];
    }
    rasterize(x, y, z, static_cast<std::uint32_t>(t), L.width, L.height, frags);
  }
  // 2. Per pixel in depth order; fragments closer than GL's depth precision (2^-22 of the range)
  //    are one layer there, the first drawn (lowest triangle id) winning as under GL_LESS.
  std::sort(frags.begin(), frags.end(), [](const Fragment& p, const Fragment& q) {
    if (p.pixel != q.pixel) return p.pixel < q.pixel;
    if (p.depth != q.depth) return p.depth < q.depth;
    return p.triangle < q.triangle;
  });
  const double tie = grid.cells[static_cast<std::size_t>(axis)] * double(grid.pixel) * std::ldexp(1.0, -22);
  const std::size_t pixels = static_cast<std::size_t>(L.width) * static_cast<std::size_t>(L.height);
  L.offsets.assign(pixels + 1, 0);
  std::size_t f = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    int count = 0;
    double last = -INFINITY;
    for (; f < frags.size() && frags[f].pixel == p; ++f) {
      if (count >= options.max_layers || frags[f].depth - last <= tie) continue;
      last = frags[f].depth;
      L.triangles.push_back(frags[f].triangle);
      ++count;
    }
    L.layers = std::max(L.layers, count);
    L.offsets[p + 1] = static_cast<std::uint32_t>(L.triangles.size());
  }
  return L;
}

}  // namespace

std::array<AxisLayers, 3> peel_layers_cpu(const TriangleMesh& mesh, const SampleGrid& grid, const SampleOptions& options) {
  std::array<AxisLayers, 3> out;
  ParallelErrors errors;  // a std::bad_alloc of one axis' fragments must not std::terminate
#pragma omp parallel for schedule(dynamic, 1)
  for (int axis = 0; axis < 3; ++axis)
    errors.run(axis, [&] { out[static_cast<std::size_t>(axis)] = peel_axis(mesh, grid, options, axis); });
  errors.rethrow();
  return out;
}

}  // namespace qf
