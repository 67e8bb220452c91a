// Vertex-clustering LOD meshes with thick edges (seed 002, Low & Tan; method.md 10): vertices graded
// by visual importance, grouped by floating cells centred on the heaviest vertices (found through a
// grid of cell-sized buckets, at most 8 per lookup), then every triangle re-made from its vertices'
// clusters: triangles that keep 3 clusters stay, those collapsing to 2 become thick edges, to 1 a
// point; duplicates and parts of larger primitives are removed. Every level comes from the
// original mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "core/types.h"

namespace qf {

// Vertex weights and the visiting order (O(N log N), once per mesh, shared by every level).
struct VertexGrading {
  std::vector<float> weight;         // per vertex, in [0, 1]
  std::vector<std::uint32_t> order;  // vertices by decreasing weight, ties by index
};

// weight = cos(theta / 2) * (longest incident edge / the mesh's longest edge): theta is the largest
// angle between two incident edges (paper 3.1: cos(theta/2) is the share of view directions from
// which the vertex can be on the silhouette), the edge factor the size of the faces it bounds
// (Rossignac & Borrel). Both lie in [0, 1] and the product makes a vertex important only when both
// are high; it is scale-invariant, and adding geometry elsewhere scales every weight alike, so the
// order of the other vertices (and their clusters) stays the same. Unused vertices weigh 0.
VertexGrading grade_vertices(const TriangleMesh& mesh);

struct ClusterOptions {
  float cell = 0;  // cell width, model units (> 0)
  enum class Shape { kCube, kSphere } shape = Shape::kCube;
  // Where a vertex inside several cells goes: the nearest centre (paper 3.2.3, the default) or the
  // heaviest centre (the original floating cells).
  enum class Assign { kNearest, kHeaviest } assign = Assign::kNearest;
  // Rossignac-Borrel's uniform subdivision instead: a fixed grid from the bounding box's corner,
  // one cluster per occupied grid cell, its vertex the weighted mean of the members.
  bool uniform = false;
};

// One LOD: vertices (one per cluster that is used), triangles, thick edges, points.
struct LodMesh {
  float cell = 0;
  std::vector<Vec3f> positions;  // floating cells: each cluster's centre vertex (the heaviest)
  std::vector<Rgb8> colors;      // the representative's colour, when the mesh has colours
  std::vector<Triangle> triangles;
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::vector<float> thickness;  // per edge, model units: D_A + D_B (paper 3.3.1)
  std::vector<std::uint32_t> points;
  std::vector<std::uint32_t> vertex_of;  // per input vertex: its output vertex (UINT32_MAX when unused)
  std::size_t clusters = 0;              // before unused ones were dropped
};

LodMesh cluster_mesh(const TriangleMesh& mesh, const VertexGrading& grading, const ClusterOptions& options);

// A runtime's level choice (paper 4): R = 2 D tan(fov / 2) / window height is the model size of a
// pixel at distance D; take the largest cell <= X * R (X = 5 by default, the paper's 5..10), else
// the smallest cell. `cells` in any order; returns an index into it.
std::size_t choose_lod(const std::vector<float>& cells, double distance, double fovy_degrees, int window_height, double x = 5);

}  // namespace qf
