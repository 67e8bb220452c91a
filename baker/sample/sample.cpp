// Mesh sampling: the grid, the point of each kept layer fragment, and the entry point (sample.h).
#include "sample/sample.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "core/error.h"
#include "core/input_limits.h"
#include "core/parallel_errors.h"
#include "core/random.h"
#include "sample/surface_color.h"

namespace qf {
namespace {

struct FaceNormal {
  double n[3] = {0, 0, 0};
  bool ok = false;
};

FaceNormal face_normal(const TriangleMesh& mesh, std::size_t t) {
  const Triangle& tri = mesh.triangles[t];
  const Vec3f a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
  const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  FaceNormal f;
  f.n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  f.n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  f.n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  const double len = std::sqrt(f.n[0] * f.n[0] + f.n[1] * f.n[1] + f.n[2] * f.n[2]);
  if (!(len > 0)) return f;
  for (double& x : f.n) x /= len;
  f.ok = true;
  return f;
}

int largest_component(const FaceNormal& f) {
  if (!f.ok) return -1;
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(f.n[k]) > std::fabs(f.n[axis])) axis = k;
  return axis;
}

}  // namespace

int sampling_axis(const TriangleMesh& mesh, std::size_t triangle) { return largest_component(face_normal(mesh, triangle)); }

SampleGrid sample_grid(const TriangleMesh& mesh, int ldi_size) {
  Bounds b;
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t i : t) b.add(mesh.positions[i]);
  const Vec3f size = b.size();
  const float longest = std::max({size.x, size.y, size.z});
  SampleGrid g;
  g.pixel = longest > 0 ? longest / static_cast<float>(ldi_size) : 1.0f;
  // Whole pixels plus one of margin on each side, the box centred in them.
  for (int k = 0; k < 3; ++k) {
    const int cells = static_cast<int>(std::ceil(size[k] / g.pixel)) + 2;
    g.cells[static_cast<std::size_t>(k)] = cells;
    g.origin[k] = b.center()[k] - 0.5f * static_cast<float>(cells) * g.pixel;
  }
  return g;
}

namespace {

// What every pixel of every axis needs about the mesh, computed once.
struct MeshFacts {
  std::vector<FaceNormal> normals;
  std::vector<int> axis_of;  // sampling axis per triangle (-1: degenerate)
  bool smooth, coloured, materials, shaded;
};

MeshFacts mesh_facts(const TriangleMesh& mesh) {
  MeshFacts f;
  f.normals.resize(mesh.triangles.size());
  f.axis_of.resize(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    f.normals[t] = face_normal(mesh, t);
    f.axis_of[t] = largest_component(f.normals[t]);
  }
  f.smooth = mesh.normals.size() == mesh.positions.size();
  f.coloured = mesh.colors.size() == mesh.positions.size();
  // Material meshes (glTF, OBJ + MTL) take their colour as glTF defines it; meshes without
  // materials (PLY, OFF) keep their vertex colours interpolated as stored, as they always were.
  f.materials = !mesh.triangle_materials.empty();
  f.shaded = f.materials && mesh.has_surface_color();
  return f;
}

// The points of image rows [j0, j1) of the layers `L`, in pixel order, appended to `out`.
void row_points(const TriangleMesh& mesh, const SampleGrid& grid, const AxisLayers& L, const MeshFacts& m, int j0, int j1,
                PointSet& out, std::vector<std::uint32_t>& triangles) {
  const int a = L.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const double s = grid.pixel;
  for (int j = j0; j < j1; ++j)
    for (int i = 0; i < L.width; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * static_cast<std::size_t>(L.width) + static_cast<std::size_t>(i);
      for (std::uint32_t f = L.offsets[p]; f < L.offsets[p + 1]; ++f) {
        const std::uint32_t t = L.triangles[f];
        if (m.axis_of[t] != a) continue;  // another axis samples this patch
        const Triangle& tri = mesh.triangles[t];
        const FaceNormal& n = m.normals[t];
        // 1. The pixel centre on the triangle's plane.
        const double pu = grid.origin[u] + (i + 0.5) * s, pv = grid.origin[v] + (j + 0.5) * s;
        const Vec3f A = mesh.positions[tri[0]];
        const double pa = A[a] - (n.n[u] * (pu - A[u]) + n.n[v] * (pv - A[v])) / n.n[a];
        Vec3f pos;
        pos[a] = static_cast<float>(pa), pos[u] = static_cast<float>(pu), pos[v] = static_cast<float>(pv);
        // 2. Barycentric weights in the image plane (clamped: GL may find a triangle for a
        //    centre a hair outside it).
        double w[3];
        const Vec3f B = mesh.positions[tri[1]], C = mesh.positions[tri[2]];
        const double det = (double(B[u]) - A[u]) * (double(C[v]) - A[v]) - (double(B[v]) - A[v]) * (double(C[u]) - A[u]);
        w[1] = ((pu - A[u]) * (double(C[v]) - A[v]) - (pv - A[v]) * (double(C[u]) - A[u])) / det;
        w[2] = ((double(B[u]) - A[u]) * (pv - A[v]) - (double(B[v]) - A[v]) * (pu - A[u])) / det;
        w[0] = 1 - w[1] - w[2];
        double sum = 0;
        for (double& x : w) sum += (x = std::clamp(x, 0.0, 1.0));
        for (double& x : w) x /= sum;
        SurfaceColor material;
        if (m.materials) {
          material = surface_color(mesh, t, w);
          if (!material.surface) continue;  // an alpha cut-out: no surface here
        }
        out.positions.push_back(pos);
        triangles.push_back(t);
        // 3. Normal, colour, radius.
        Vec3f normal{static_cast<float>(n.n[0]), static_cast<float>(n.n[1]), static_cast<float>(n.n[2])};
        if (m.smooth) {
          Vec3f sm{};
          for (int k = 0; k < 3; ++k) sm = sm + mesh.normals[tri[static_cast<std::size_t>(k)]] * static_cast<float>(w[k]);
          normal = normalized(sm, normal);
        }
        out.normals.push_back(normal);
        if (m.shaded) {
          out.colors.push_back(material.color);
        } else if (m.coloured) {
          out.colors.push_back(interpolated_vertex_color(mesh, t, w));
        }
        out.radii.push_back(static_cast<float>(0.5 * s * std::sqrt(1 + 1 / (n.n[a] * n.n[a]))));
      }
    }
}

// Moves `src` to the end of `dst`.
template <class T>
void move_to_end(std::vector<T>& dst, std::vector<T>& src) {
  dst.insert(dst.end(), src.begin(), src.end());
  std::vector<T>().swap(src);
}

// Moves `part`'s points to the end of `out`.
void append_points(PointSet& out, PointSet& part) {
  move_to_end(out.positions, part.positions), move_to_end(out.normals, part.normals), move_to_end(out.colors, part.colors);
  move_to_end(out.radii, part.radii);
}

// Keeps the points (and their triangles) flagged in `keep`, in order.
void keep_points(PointSet& points, std::vector<std::uint32_t>& triangles, const std::vector<char>& keep) {
  std::vector<std::uint32_t> order;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) order.push_back(static_cast<std::uint32_t>(i));
  if (order.size() == keep.size()) return;
  points = permuted(points, order);
  std::vector<std::uint32_t> kept(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) kept[k] = triangles[order[k]];
  triangles = std::move(kept);
}

// Bytes the layers and points of `mesh` on `grid` will take, estimated before any is drawn: per
// triangle and axis it is drawn on, its fragments (its projected area in pixels, plus its
// perimeter and a corner for the pixels its edges touch), each 24 bytes in a vector that may
// double and 4 as a layer entry; per axis the pixel offsets; per kept fragment (at most
// max_layers a pixel) a point of ~64 bytes as its row blocks and the joined set hold it. An
// upper bound for closed meshes, whose points are fewer than their fragments.
double estimated_sampling_bytes(const TriangleMesh& mesh, const SampleGrid& grid, const SampleOptions& options) {
  std::array<double, 3> fragments{};
  const double px = double(grid.pixel);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3f& a = mesh.positions[mesh.triangles[t][0]];
    const Vec3f& b = mesh.positions[mesh.triangles[t][1]];
    const Vec3f& c = mesh.positions[mesh.triangles[t][2]];
    const Vec3f n = cross(b - a, c - a);
    const double perimeter = (double(length(b - a)) + double(length(c - b)) + double(length(a - c))) / px;
    for (int axis = 0; axis < 3; ++axis) {
      if (options.per_axis_triangles && sampling_axis(mesh, t) != axis) continue;
      fragments[static_cast<std::size_t>(axis)] += std::abs(double(n[axis])) / 2 / (px * px) + perimeter + 1;
    }
  }
  double total = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double pixels = double(grid.width(axis)) * double(grid.height(axis));
    const double f = fragments[static_cast<std::size_t>(axis)];
    total += f * (2 * 24 + 4) + (pixels + 1) * 4 + std::min(f, pixels * options.max_layers) * 64;
  }
  return total;
}

}  // namespace

PointSet points_from_layers(const TriangleMesh& mesh, const SampleGrid& grid, const std::array<AxisLayers, 3>& layers,
                            SampleStats* stats, std::vector<std::uint32_t>* triangles) {
  const MeshFacts facts = mesh_facts(mesh);
  PointSet out;
  std::vector<std::uint32_t> out_triangles;
  for (const AxisLayers& L : layers) {
    // Blocks of rows on both cores (a textured mesh spends most of its sampling here, in texture
    // lookups), joined in row order: the points do not depend on the thread count.
    constexpr int kRows = 8;
    const int blocks = (L.height + kRows - 1) / kRows;
    std::vector<PointSet> parts(static_cast<std::size_t>(std::max(blocks, 0)));
    std::vector<std::vector<std::uint32_t>> part_triangles(parts.size());
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
    for (int b = 0; b < blocks; ++b)
      errors.run(b, [&] {
        row_points(mesh, grid, L, facts, b * kRows, std::min(L.height, (b + 1) * kRows), parts[static_cast<std::size_t>(b)],
                   part_triangles[static_cast<std::size_t>(b)]);
      });
    errors.rethrow();
    const std::size_t before = out.size();
    for (std::size_t b = 0; b < parts.size(); ++b) {
      append_points(out, parts[b]);
      move_to_end(out_triangles, part_triangles[b]);
    }
    if (stats) {
      stats->layers[static_cast<std::size_t>(L.axis)] = L.layers;
      stats->points[static_cast<std::size_t>(L.axis)] = out.size() - before;
      stats->fragments += L.triangles.size();
    }
  }
  if (stats) {
    stats->pixel = grid.pixel;
    stats->degenerate_triangles = static_cast<std::size_t>(std::count(facts.axis_of.begin(), facts.axis_of.end(), -1));
  }
  if (triangles) *triangles = std::move(out_triangles);
  return out;
}

PointSet sample_mesh(const TriangleMesh& mesh, const SampleOptions& options, const std::string& source, SampleStats* stats,
                     std::vector<std::uint32_t>* triangles) {
  // 1. A mesh we can sample: triangles, indices in range, finite corners.
  if (mesh.triangles.empty()) throw InputError("mesh.no_triangles", source, "", "is a mesh without triangles; nothing to sample");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t i : mesh.triangles[t]) {
      if (i >= mesh.positions.size())
        throw InputError("mesh.bad_index", source, "triangle " + std::to_string(t),
                         "uses vertex " + std::to_string(i) + "; the mesh has " + std::to_string(mesh.positions.size()));
      if (!is_finite(mesh.positions[i]))
        throw InputError("mesh.nonfinite", source, "vertex " + std::to_string(i),
                         "has a non-finite coordinate (see --drop-nonfinite)");
    }
  if (options.ldi_size < 2 || options.ldi_size > 16000) throw UsageError("the LDI size must be 2..16000 pixels");
  // 2. Layers by the chosen backend (GL falls back to the CPU when no context can be made).
  const auto start = std::chrono::steady_clock::now();
  const SampleGrid grid = sample_grid(mesh, options.ldi_size);
  check_memory_need(static_cast<std::uint64_t>(std::min(estimated_sampling_bytes(mesh, grid, options), 1e19)), options.memory_limit,
                    source, "sample.memory", "",
                    "sampling its " + std::to_string(mesh.triangles.size()) + " triangles at LDI " + std::to_string(options.ldi_size));
  SampleStats local;
  SampleStats& st = stats ? *stats : local;
  std::array<AxisLayers, 3> layers;
  st.backend = options.backend;
  if (options.backend == "gl") {
    try {
      layers = peel_layers_gl(mesh, grid, options);
    } catch (const std::runtime_error& e) {
      st.backend = "cpu";
      st.fallback = std::string("GL unavailable (") + e.what() + "), sampled on the CPU";
      layers = peel_layers_cpu(mesh, grid, options);
    }
  } else if (options.backend == "cpu") {
    layers = peel_layers_cpu(mesh, grid, options);
  } else {
    throw UsageError("unknown sampler backend '" + options.backend + "' (gl or cpu)");
  }
  std::vector<std::uint32_t> point_triangles;
  PointSet points = points_from_layers(mesh, grid, layers, &st, &point_triangles);
  // 3. Only what an outside view sees.
  const std::size_t sampled = points.size();
  keep_points(points, point_triangles, visible_points(mesh, points.positions, grid.pixel, options.visibility));
  st.hidden = sampled - points.size();
  if (triangles) *triangles = std::move(point_triangles);
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (points.size() == 0)
    throw InputError("mesh.no_points", source, "", "gave no points at LDI size " + std::to_string(options.ldi_size) +
                                                       " (all triangles degenerate or smaller than a pixel?)");
  return points;
}

std::vector<std::uint32_t> point_permutation(std::size_t n, std::uint64_t seed) {
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  SplitMix64 random(seed);
  for (std::size_t i = n; i > 1; --i) {
    // Unbiased enough: 2^64 / i leaves a bias below 2^-32 for any i < 2^32.
    const std::size_t j = static_cast<std::size_t>(random.next() % i);
    std::swap(order[i - 1], order[j]);
  }
  return order;
}

}  // namespace qf
