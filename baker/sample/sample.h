// Triangle meshes -> point sets by depth peeling along the three axes (seed 001, Baerentzen;
// method.md 9). The mesh is seen orthographically along X, Y and Z on a common pixel grid; every
// depth layer of every pixel is found (no back-face culling: soups, open and non-manifold meshes
// work), and a layer's fragment becomes a point only on the axis its triangle's normal is most
// parallel to, so each surface patch is sampled once.
//
// Two backends find the layers: OpenGL depth peeling through EGL (a 32-bit float depth texture and
// an exact comparison, gl-notes.md 3) and a CPU rasterizer with the same coverage rule (pixel
// centres, top-left edges). Both give, per axis and pixel, the triangles hit in depth order; the
// points are made from them by one shared function, so the backends differ only where a pixel
// centre lies on an edge (GL snaps vertices to 1/256 pixel).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "sample/visibility.h"

namespace qf {

struct SampleOptions {
  // Largest side of the layered depth image, pixels: pixel side s = the bounding box's longest
  // extent / ldi_size. 256 gives 50k-500k points on typical models (elephant 67k, bunny00 133k,
  // cube 393k: about 1.7 ldi_size^2 for compact shapes).
  int ldi_size = 256;
  // The faster variant (paper 2.1), on by default: each axis draws only the triangles whose normal
  // is most parallel to it. Points are selected by the triangle's normal in both variants, so it
  // gives the same points with fewer layers (bunny00 at 1000: 3/4/4 layers instead of 10/8/10,
  // GL 0.87 s instead of 1.58 s).
  bool per_axis_triangles = true;
  int max_layers = 64;       // a cap per axis: grazing spots can make long, sparse tails
  // "cpu" (default) or "gl". On the 2-core build machines (Mesa llvmpipe, no GPU) the CPU
  // rasterizer is faster at every size measured (bunny00 at LDI 1000: 0.29 s vs 0.56 s; at 100:
  // 0.015 s vs 0.12 s, scripts/bench.sh sample) and its points do not depend on the Mesa version,
  // which keeps bakes byte-identical across machines. GL gives the same points but 0.01%.
  std::string backend = "cpu";
  // Points no outside view sees are dropped (visible_points): the inside of a closed housing and
  // the parts within it show in no camera, and would colour the quads of the shell around them.
  // visibility.views = 0 keeps every layer.
  VisibilityOptions visibility;
  // Bytes sampling may take (qf-bake --max-memory); 0: the memory available (core/memory.h).
  // The layers' fragments and points are estimated from the triangles' areas in pixels before
  // any is drawn; past the limit sample_mesh throws InputError "sample.memory" (a mesh of 10^6
  // overlapping cubes, or --ldi 16000, took all memory, then std::bad_alloc in a parallel loop).
  std::size_t memory_limit = 0;
};

// One axis' layered depth image, as triangle ids: for pixel p (row-major, row 0 at the grid's
// lowest v), the triangles hit at increasing depth are triangles[offsets[p] .. offsets[p+1]).
struct AxisLayers {
  int axis = 0;  // 0 = X (image axes u = Y, v = Z), 1 = Y (u = Z, v = X), 2 = Z (u = X, v = Y)
  int width = 0, height = 0;
  int layers = 0;  // the deepest pixel's count
  std::vector<std::uint32_t> offsets;    // width * height + 1
  std::vector<std::uint32_t> triangles;  // per fragment
};

// The common pixel grid: pixel (i, j) of axis a has its centre at u = u0 + (i + 0.5) s,
// v = v0 + (j + 0.5) s in the axis' image coordinates.
struct SampleGrid {
  float pixel = 0;                // s, model units
  Vec3f origin;                   // grid corner (the bounding box's minimum, centred in the grid)
  std::array<int, 3> cells{};     // pixels along X, Y, Z
  int width(int axis) const { return cells[static_cast<std::size_t>((axis + 1) % 3)]; }
  int height(int axis) const { return cells[static_cast<std::size_t>((axis + 2) % 3)]; }
};

// Axis `axis`'s layers with the grid's image size and nothing found yet, for a backend to fill.
inline AxisLayers empty_layers(const SampleGrid& grid, int axis) {
  AxisLayers L;
  L.axis = axis;
  L.width = grid.width(axis);
  L.height = grid.height(axis);
  return L;
}

struct SampleStats {
  std::string backend;                 // what actually ran ("gl" or "cpu")
  float pixel = 0;                     // s
  std::array<int, 3> layers{};         // per axis
  std::array<std::size_t, 3> points{};  // per axis
  std::size_t fragments = 0;           // every layer pixel, kept or not
  std::size_t degenerate_triangles = 0;  // zero area: no normal, never sampled
  std::size_t hidden = 0;              // points dropped as seen from no outside view
  std::string fallback;                // why GL was not used, when it was asked for
  double seconds = 0;
};

// The grid for a mesh: square pixels of side longest extent / ldi_size, one pixel of margin.
SampleGrid sample_grid(const TriangleMesh& mesh, int ldi_size);

// The layers of every axis, by either backend. The GL backend throws std::runtime_error when no
// GL context can be made.
std::array<AxisLayers, 3> peel_layers_cpu(const TriangleMesh& mesh, const SampleGrid& grid, const SampleOptions& options);
std::array<AxisLayers, 3> peel_layers_gl(const TriangleMesh& mesh, const SampleGrid& grid, const SampleOptions& options);

// The point set from the layers: position = pixel centre at the triangle's depth, normal = the
// vertex normals interpolated (else the triangle's), colour = the material's (surface_color.h:
// base colour x texture x vertex colour) for meshes with materials, else the vertex colours
// interpolated (none when the mesh has none); fragments where a MASK material is cut out give no
// point, radius = half the diagonal of the pixel's footprint on the triangle's
// plane, (s/2) sqrt(1 + 1/n_a^2). Points in axis, pixel, depth order. `triangles`, when given,
// receives each point's triangle.
PointSet points_from_layers(const TriangleMesh& mesh, const SampleGrid& grid, const std::array<AxisLayers, 3>& layers,
                            SampleStats* stats = nullptr, std::vector<std::uint32_t>* triangles = nullptr);

// Checks the mesh (throws InputError "mesh.no_triangles" / "mesh.bad_index" / "mesh.nonfinite"
// naming `source`), samples it with the chosen backend and keeps the points an outside view sees
// (options.visibility). `triangles`, when given, receives each point's triangle: what a mesh
// input's quads draw (primitives/texture.h MeshSurface).
PointSet sample_mesh(const TriangleMesh& mesh, const SampleOptions& options, const std::string& source,
                     SampleStats* stats = nullptr, std::vector<std::uint32_t>* triangles = nullptr);

// Point impostors (paper section 5): a random permutation of the n sampled points, the same for
// the same seed on every platform (splitmix64 + Fisher-Yates). Drawing any prefix of the permuted
// set gives an evenly thinned sampling.
// (core/types.h permuted applies it.)
std::vector<std::uint32_t> point_permutation(std::size_t n, std::uint64_t seed);

// The axis a triangle is sampled on: the largest |normal component|, the lowest axis on ties; -1
// for a degenerate triangle.
int sampling_axis(const TriangleMesh& mesh, std::size_t triangle);

}  // namespace qf
