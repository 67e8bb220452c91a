// Vertex clustering (see clustering.h; Low & Tan 1997, sections 3-4).
#include "clustering/clustering.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace qf {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

std::uint64_t bucket_key(std::int64_t x, std::int64_t y, std::int64_t z) {
  // 21 bits per axis, offset so negative coordinates pack too; only used for lookups.
  const auto f = [](std::int64_t v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1FFFFF; };
  return f(x) << 42 | f(y) << 21 | f(z);
}

// The grid of cell-sized buckets, anchored at the origin (so adding geometry elsewhere moves no
// bucket). Bucket heads live in a dense array over the used vertices' box when that box has few
// buckets for the vertex count, else in a flat open-addressing table sized by the vertex count (at
// fine cells a dense array would be mostly empty, and clearing it cost more than the clustering).
// Cells of a bucket form a linked list through `next`.
class BucketGrid {
 public:
  BucketGrid(const Bounds& b, double cell, std::size_t vertices) : inv_cell_(1.0 / cell) {
    std::uint64_t total = 1;
    for (int k = 0; k < 3; ++k) {
      lo_[k] = coord(b.min[k]) - 1;
      n_[k] = coord(b.max[k]) - lo_[k] + 2;
      total *= static_cast<std::uint64_t>(n_[k]);
    }
    if (total <= std::max<std::uint64_t>(4096, 16 * vertices)) {
      dense_.assign(total, kNone);
    } else {
      std::size_t cap = 64;
      while (cap < 2 * vertices) cap *= 2;  // at most one cell per vertex: never more than half full
      slots_.assign(cap, Slot{kEmpty, kNone});
    }
  }
  // The bucket of a coordinate. Any monotonic map works (a centre within h of p then lies in the
  // buckets of p - h .. p + h); a multiplication is 5x cheaper than the division by the cell.
  std::int64_t coord(double x) const { return static_cast<std::int64_t>(std::floor(x * inv_cell_)); }
  std::uint32_t head(std::int64_t x, std::int64_t y, std::int64_t z) const {
    if (!dense_.empty()) return dense_[index(x, y, z)];
    const std::uint64_t key = bucket_key(x, y, z);
    for (std::size_t i = slot(key);; i = (i + 1) & (slots_.size() - 1)) {
      if (slots_[i].key == key) return slots_[i].head;
      if (slots_[i].key == kEmpty) return kNone;
    }
  }
  void push(std::int64_t x, std::int64_t y, std::int64_t z, std::uint32_t cell, std::vector<std::uint32_t>& next) {
    std::uint32_t* h = nullptr;
    if (!dense_.empty()) {
      h = &dense_[index(x, y, z)];
    } else {
      const std::uint64_t key = bucket_key(x, y, z);
      std::size_t i = slot(key);
      while (slots_[i].key != key && slots_[i].key != kEmpty) i = (i + 1) & (slots_.size() - 1);
      slots_[i].key = key;
      h = &slots_[i].head;
    }
    next.push_back(*h);
    *h = cell;
  }

 private:
  struct Slot {
    std::uint64_t key;
    std::uint32_t head;
  };
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // bucket_key never makes it (63 bits)
  std::size_t slot(std::uint64_t key) const {
    const std::uint64_t h = key * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(h >> 32) & (slots_.size() - 1);
  }
  std::size_t index(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return static_cast<std::size_t>(((x - lo_[0]) * n_[1] + (y - lo_[1])) * n_[2] + (z - lo_[2]));
  }
  double inv_cell_;
  std::int64_t lo_[3] = {0, 0, 0}, n_[3] = {1, 1, 1};
  std::vector<std::uint32_t> dense_;
  std::vector<Slot> slots_;
};

// Floating cells through a grid of cell-sized buckets: a cell is filed under the bucket of its
// centre; the centres that can hold a vertex lie within half a cell of it, in at most 2 buckets
// per axis, so at most 8 buckets are searched (paper 4).
std::vector<std::uint32_t> floating_cells(const TriangleMesh& mesh, const std::vector<bool>& used, const VertexGrading& g,
                                          const ClusterOptions& o, std::vector<std::uint32_t>& centers) {
  const double h = 0.5 * o.cell;
  Bounds box;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (used[v]) box.add(mesh.positions[v]);
  BucketGrid grid(box, o.cell, mesh.positions.size());
  std::vector<std::uint32_t> next;   // per cell: the next cell in its bucket
  std::vector<Vec3f> center_of;      // per cell: its centre (one load per candidate, not three)
  std::vector<std::uint32_t> cluster(mesh.positions.size(), kNone);
  for (std::size_t i = 0; i < g.order.size(); ++i) {
    // The weight order is spatially random: fetch a vertex a few steps ahead of its turn.
    if (i + 8 < g.order.size()) __builtin_prefetch(&mesh.positions[g.order[i + 8]]);
    const std::uint32_t v = g.order[i];
    if (!used[v]) continue;
    const Vec3f p = mesh.positions[v];
    std::int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = grid.coord(static_cast<float>(p[k] - h));
      hi[k] = grid.coord(static_cast<float>(p[k] + h));
    }
    std::uint32_t best = kNone;
    double best_d2 = INFINITY;
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          for (std::uint32_t cell = grid.head(x, y, z); cell != kNone; cell = next[cell]) {
            const Vec3f q = center_of[cell];
            const double d[3] = {double(p.x) - q.x, double(p.y) - q.y, double(p.z) - q.z};
            const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            const bool inside = o.shape == ClusterOptions::Shape::kCube
                                    ? std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])}) <= h
                                    : d2 <= h * h;
            if (!inside) continue;
            // Nearest centre (ties: the heavier, i.e. older, cell), or simply the heaviest.
            const bool better = o.assign == ClusterOptions::Assign::kNearest ? (d2 < best_d2 || (d2 == best_d2 && cell < best))
                                                                              : cell < best;
            if (better) best = cell, best_d2 = d2;
          }
    if (best == kNone) {
      best = static_cast<std::uint32_t>(centers.size());
      centers.push_back(v);
      center_of.push_back(p);
      grid.push(grid.coord(p.x), grid.coord(p.y), grid.coord(p.z), best, next);
    }
    cluster[v] = best;
  }
  return cluster;
}

// Rossignac-Borrel: one cluster per occupied cell of a grid anchored at the bounding box's corner;
// clusters numbered in visiting order, their heaviest member first.
std::vector<std::uint32_t> uniform_cells(const TriangleMesh& mesh, const std::vector<bool>& used, const VertexGrading& g,
                                         const ClusterOptions& o, std::vector<std::uint32_t>& heaviest) {
  Bounds b;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (used[v]) b.add(mesh.positions[v]);
  std::vector<std::uint32_t> cluster(mesh.positions.size(), kNone);
  std::unordered_map<std::uint64_t, std::uint32_t> ids;
  for (std::uint32_t v : g.order) {
    if (!used[v]) continue;
    const Vec3f p = mesh.positions[v] - b.min;
    const std::uint64_t key = bucket_key(static_cast<std::int64_t>(p.x / o.cell), static_cast<std::int64_t>(p.y / o.cell),
                                         static_cast<std::int64_t>(p.z / o.cell));
    const auto [it, fresh] = ids.insert({key, static_cast<std::uint32_t>(heaviest.size())});
    if (fresh) heaviest.push_back(v);
    cluster[v] = it->second;
  }
  return cluster;
}

// A set of 96-bit keys by open addressing (linear probing in one array): the per-level duplicate
// tests without a node allocation per entry. Only used for membership, never iterated.
class KeySet {
 public:
  explicit KeySet(std::size_t n) {
    std::size_t cap = 16;
    while (cap < 2 * n) cap *= 2;
    slots_.assign(cap, {kNone, kNone, kNone});
  }
  // Inserts k (whose first word is not kNone); false when it was already there.
  bool insert(const std::array<std::uint32_t, 3>& k) {
    std::array<std::uint32_t, 3>& slot = find(k);
    if (slot[0] != kNone) return false;
    slot = k;
    return true;
  }
  bool contains(const std::array<std::uint32_t, 3>& k) { return find(k)[0] != kNone; }

 private:
  // k's slot, or the empty slot where it would go (linear probing; the table is never full).
  std::array<std::uint32_t, 3>& find(const std::array<std::uint32_t, 3>& k) {
    const std::size_t mask = slots_.size() - 1;
    const std::uint64_t h = (std::uint64_t{k[0]} * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t{k[1]} * 0xC2B2AE3D27D4EB4Full) ^ k[2];
    std::size_t i = static_cast<std::size_t>(h ^ (h >> 29)) & mask;
    // Word by word (std::array's == goes through memcmp, a call per probe).
    while (slots_[i][0] != kNone && (slots_[i][0] != k[0] || slots_[i][1] != k[1] || slots_[i][2] != k[2])) i = (i + 1) & mask;
    return slots_[i];
  }
  std::vector<std::array<std::uint32_t, 3>> slots_;
};

// Distance of p from the line through a and b.
double line_distance(Vec3f p, Vec3f a, Vec3f b) {
  const Vec3f d = b - a;
  const double len = length(d);
  if (!(len > 0)) return length(p - a);
  return length(cross(p - a, d)) / len;
}

}  // namespace

VertexGrading grade_vertices(const TriangleMesh& mesh) {
  const std::size_t n = mesh.positions.size();
  // 1. Incident edge directions and the longest incident edge per vertex.
  std::vector<std::vector<Vec3f>> dirs(n);
  std::vector<float> longest(n, 0);
  float mesh_longest = 0;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      const Vec3f e = mesh.positions[b] - mesh.positions[a];
      const float len = length(e);
      if (!(len > 0)) continue;
      dirs[a].push_back(e * (1 / len));
      dirs[b].push_back(e * (-1 / len));
      longest[a] = std::max(longest[a], len);
      longest[b] = std::max(longest[b], len);
      mesh_longest = std::max(mesh_longest, len);
    }
  // 2. theta = the largest angle between two incident edges (each edge appears twice; harmless).
  VertexGrading g;
  g.weight.assign(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    if (dirs[v].empty() || !(mesh_longest > 0)) continue;
    float min_cos = 1;
    for (std::size_t i = 0; i < dirs[v].size(); ++i)
      for (std::size_t j = i + 1; j < dirs[v].size(); ++j) min_cos = std::min(min_cos, dot(dirs[v][i], dirs[v][j]));
    const double theta = std::acos(std::clamp(double(min_cos), -1.0, 1.0));
    g.weight[v] = static_cast<float>(std::cos(theta / 2) * (longest[v] / mesh_longest));
  }
  // 3. Visiting order: decreasing weight, ties by index (stable, so deterministic).
  g.order.resize(n);
  for (std::size_t i = 0; i < n; ++i) g.order[i] = static_cast<std::uint32_t>(i);
  std::stable_sort(g.order.begin(), g.order.end(), [&](std::uint32_t a, std::uint32_t b) { return g.weight[a] > g.weight[b]; });
  return g;
}

namespace {

// A triangle whose three clusters differ (key: the clusters sorted; t: them in its winding), and a
// triangle collapsed to the edge between two clusters (a < b).
struct ClusterTri {
  std::array<std::uint32_t, 3> key;
  Triangle t;
  std::size_t index;
};
struct ClusterEdge {
  std::uint32_t a, b;
  std::size_t triangle;
};

// The clusters' positions: the representative's (floating cells), or the weighted mean of the
// members (uniform grid; the plain mean where all weigh 0).
std::vector<Vec3f> cluster_positions(const TriangleMesh& mesh, const VertexGrading& g, bool uniform,
                                     const std::vector<std::uint32_t>& cluster, const std::vector<std::uint32_t>& rep) {
  std::vector<Vec3f> pos(rep.size());
  for (std::size_t c = 0; c < rep.size(); ++c) pos[c] = mesh.positions[rep[c]];
  if (!uniform) return pos;
  std::vector<double> sum(rep.size() * 4, 0.0);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (cluster[v] == kNone) continue;
    const double w = g.weight[v] > 0 ? g.weight[v] : 1e-9;
    double* s = &sum[cluster[v] * 4];
    s[0] += w * mesh.positions[v].x, s[1] += w * mesh.positions[v].y, s[2] += w * mesh.positions[v].z, s[3] += w;
  }
  for (std::size_t c = 0; c < rep.size(); ++c)
    pos[c] = {static_cast<float>(sum[c * 4] / sum[c * 4 + 3]), static_cast<float>(sum[c * 4 + 1] / sum[c * 4 + 3]),
              static_cast<float>(sum[c * 4 + 2] / sum[c * 4 + 3])};
  return pos;
}

// Synthesis: each triangle by its clusters, as a triangle, an edge, or a point (`point[c]`: some
// triangle collapsed into cluster c).
void synthesize(const TriangleMesh& mesh, const std::vector<std::uint32_t>& cluster, std::vector<ClusterTri>& tris,
                std::vector<ClusterEdge>& edges, std::vector<bool>& point) {
  tris.reserve(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& t = mesh.triangles[i];
    const Triangle c{cluster[t[0]], cluster[t[1]], cluster[t[2]]};
    if (c[0] != c[1] && c[1] != c[2] && c[0] != c[2]) {
      std::array<std::uint32_t, 3> key = c;  // sorted by three compare-swaps (std::sort is a call per triangle)
      if (key[0] > key[1]) std::swap(key[0], key[1]);
      if (key[1] > key[2]) std::swap(key[1], key[2]);
      if (key[0] > key[1]) std::swap(key[0], key[1]);
      tris.push_back({key, c, i});
    } else if (c[0] != c[1] || c[1] != c[2]) {
      const std::uint32_t a = c[0], b = c[0] != c[1] ? c[1] : c[2];
      edges.push_back({std::min(a, b), std::max(a, b), i});
    } else {
      point[c[0]] = true;
    }
  }
}

// Elimination: one triangle per cluster triple (the first, with its winding); edges that are sides
// of a triangle go; `covered[c]`: cluster c is a corner of a kept triangle or an end of an edge (a
// point there adds nothing). Edges end sorted by their cluster pair.
void eliminate(std::vector<ClusterTri>& tris, std::vector<ClusterEdge>& edges, std::vector<bool>& covered) {
  {  // first occurrence of each cluster triple, in input order
    KeySet seen(tris.size());
    std::size_t kept = 0;
    for (const ClusterTri& t : tris)
      if (seen.insert(t.key)) tris[kept++] = t;
    tris.resize(kept);
  }
  // Collapsed triangles whose edge is a side of a kept triangle add nothing: drop them before
  // grouping (most of them, on fine levels), so only true thick edges get sorted.
  KeySet sides(edges.empty() ? 0 : tris.size() * 3);
  for (const ClusterTri& t : tris)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t.key[static_cast<std::size_t>(k)], b = t.key[static_cast<std::size_t>((k + 1) % 3)];
      if (!edges.empty()) sides.insert({std::min(a, b), std::max(a, b), 0});
      covered[a] = true;
    }
  std::size_t kept = 0;
  for (const ClusterEdge& e : edges) {
    covered[e.a] = covered[e.b] = true;
    if (!sides.contains({e.a, e.b, 0})) edges[kept++] = e;
  }
  edges.resize(kept);
  std::stable_sort(edges.begin(), edges.end(), [](const ClusterEdge& x, const ClusterEdge& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
}

// The output mesh, built cluster by cluster: a cluster gets its output vertex when first used.
struct LodBuilder {
  const TriangleMesh& mesh;
  const std::vector<std::uint32_t>& cluster;
  const std::vector<std::uint32_t>& rep;
  const std::vector<Vec3f>& pos;
  LodMesh& out;
  std::vector<std::uint32_t> out_id = std::vector<std::uint32_t>(rep.size(), kNone);

  std::uint32_t id(std::uint32_t c) {
    if (out_id[c] == kNone) {
      out_id[c] = static_cast<std::uint32_t>(out.positions.size());
      out.positions.push_back(pos[c]);
      if (mesh.colors.size() == mesh.positions.size()) out.colors.push_back(mesh.colors[rep[c]]);
    }
    return out_id[c];
  }

  void triangles(const std::vector<ClusterTri>& tris) {
    for (const ClusterTri& t : tris) {
      // A collapse can fold a triangle over (its cluster corners in the other winding): keep the
      // side the original faced, or smooth normals and two-sided lighting darken it.
      const Triangle& o3 = mesh.triangles[t.index];
      const Vec3f before = cross(mesh.positions[o3[1]] - mesh.positions[o3[0]], mesh.positions[o3[2]] - mesh.positions[o3[0]]);
      const Vec3f after = cross(pos[t.t[1]] - pos[t.t[0]], pos[t.t[2]] - pos[t.t[0]]);
      if (dot(before, after) < 0) out.triangles.push_back({id(t.t[0]), id(t.t[2]), id(t.t[1])});
      else out.triangles.push_back({id(t.t[0]), id(t.t[1]), id(t.t[2])});
    }
  }

  // Thick edges: per cluster pair (edges sorted by it), thickness D_A + D_B from the collapsed
  // triangles' vertices (paper 3.3.1).
  void thick_edges(const std::vector<ClusterEdge>& edges) {
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
      const std::uint32_t A = edges[i].a, B = edges[i].b;
      std::vector<std::uint32_t> va, vb;
      for (std::size_t k = i; k < j; ++k)
        for (std::uint32_t v : mesh.triangles[edges[k].triangle]) (cluster[v] == A ? va : vb).push_back(v);
      for (auto* s : {&va, &vb}) std::sort(s->begin(), s->end()), s->erase(std::unique(s->begin(), s->end()), s->end());
      auto mean = [&](const std::vector<std::uint32_t>& s) {
        Vec3f m{};
        for (std::uint32_t v : s) m = m + mesh.positions[v];
        return m * (1.0f / static_cast<float>(s.size()));
      };
      const Vec3f pa = mean(va), pb = mean(vb);
      double da = 0, db = 0;
      for (std::uint32_t v : va) da += line_distance(mesh.positions[v], pa, pb);
      for (std::uint32_t v : vb) db += line_distance(mesh.positions[v], pa, pb);
      out.edges.push_back({id(A), id(B)});
      out.thickness.push_back(static_cast<float>(da / double(va.size()) + db / double(vb.size())));
      i = j;
    }
  }
};

}  // namespace

LodMesh cluster_mesh(const TriangleMesh& mesh, const VertexGrading& g, const ClusterOptions& o) {
  if (!(o.cell > 0)) throw std::invalid_argument("cluster_mesh: the cell width must be positive");
  std::vector<bool> used(mesh.positions.size(), false);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) used[v] = true;
  // 1. Clustering.
  std::vector<std::uint32_t> rep;  // per cluster: its representative (centre / heaviest) vertex
  const std::vector<std::uint32_t> cluster = o.uniform ? uniform_cells(mesh, used, g, o, rep) : floating_cells(mesh, used, g, o, rep);
  LodMesh out;
  out.cell = o.cell;
  out.clusters = rep.size();
  const std::vector<Vec3f> cluster_pos = cluster_positions(mesh, g, o.uniform, cluster, rep);
  // 2. Synthesis, 3. elimination.
  std::vector<ClusterTri> tris;
  std::vector<ClusterEdge> edges;
  std::vector<bool> point(rep.size(), false), covered(rep.size(), false);
  synthesize(mesh, cluster, tris, edges, point);
  eliminate(tris, edges, covered);
  // 4. The output: triangles, thick edges, then the points no triangle or edge covers.
  LodBuilder build{mesh, cluster, rep, cluster_pos, out};
  out.positions.reserve(rep.size());
  if (mesh.colors.size() == mesh.positions.size()) out.colors.reserve(rep.size());
  out.triangles.reserve(tris.size());
  build.triangles(tris);
  build.thick_edges(edges);
  for (std::uint32_t c = 0; c < rep.size(); ++c)
    if (point[c] && !covered[c]) out.points.push_back(build.id(c));
  out.vertex_of.assign(mesh.positions.size(), kNone);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (cluster[v] != kNone) out.vertex_of[v] = build.out_id[cluster[v]];
  return out;
}

std::size_t choose_lod(const std::vector<float>& cells, double distance, double fovy_degrees, int window_height, double x) {
  const double r = 2 * distance * std::tan(0.5 * fovy_degrees * 3.14159265358979323846 / 180) / window_height;
  std::size_t best = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const bool fits = cells[i] <= x * r, best_fits = cells[best] <= x * r;
    if ((fits && (!best_fits || cells[i] > cells[best])) || (!fits && !best_fits && cells[i] < cells[best])) best = i;
  }
  return best;
}

}  // namespace qf
