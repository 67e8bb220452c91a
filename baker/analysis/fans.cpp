// Local Delaunay fans by Voronoi-cell clipping in the tangent plane (paper 2.2, fig. 3b).
#include "analysis/fans.h"

#include <algorithm>
#include <cmath>

namespace qf {
namespace {

struct Corner {
  double x, y;
  std::int32_t label;  // neighbour (position in the neighbourhood) whose bisector carries the edge
                       // leaving this corner; -1 for the initial box
};

class CellClipper {
 public:
  // Computes the fan of point i and appends it to `out`; returns false if the fan is open.
  bool fan(std::size_t i, const std::vector<Vec3f>& pos, const Neighborhoods& nb, const LocalFrames& f,
           std::vector<std::array<std::uint32_t, 2>>& out, std::size_t& duplicates) {
    const std::uint32_t b = nb.offsets[i], e = nb.offsets[i + 1];
    // 1. Project the neighbours onto the tangent plane (e0, e1), the point at the origin.
    proj_.clear();
    double extent2 = 0;
    for (std::uint32_t r = b; r < e; ++r) {
      const Vec3f d = pos[nb.indices[r]] - pos[i];
      const double u = double(d.x) * f.e0[i].x + double(d.y) * f.e0[i].y + double(d.z) * f.e0[i].z;
      const double v = double(d.x) * f.e1[i].x + double(d.y) * f.e1[i].y + double(d.z) * f.e1[i].z;
      proj_.push_back({u, v});
      extent2 = std::max(extent2, u * u + v * v);
    }
    if (!(extent2 > 0)) {
      duplicates += e - b;
      return true;  // no neighbours, or all coincide with the point: empty fan
    }
    const double extent = std::sqrt(extent2);
    // Corners within this distance (squared units) of a bisector count as on it: cocircular
    // neighbours then do not add a zero-length edge.
    const double tol = 1e-9 * extent2;
    const double box = 1e4 * extent;
    cell_.assign({{-box, -box, -1}, {box, -box, -1}, {box, box, -1}, {-box, box, -1}});
    double reach2 = 2 * box * box;  // squared distance of the farthest corner
    // 2. Clip by each neighbour's bisector {z : z.q <= |q|^2 / 2}.
    for (std::size_t k = 0; k < proj_.size(); ++k) {
      const double qx = proj_[k][0], qy = proj_[k][1];
      const double q2 = qx * qx + qy * qy;
      if (q2 <= tol) {
        ++duplicates;
        continue;
      }
      if (q2 > 4 * reach2) continue;  // its bisector lies beyond every corner
      if (clip(qx, qy, 0.5 * q2, tol, static_cast<std::int32_t>(k))) {
        reach2 = 0;
        for (const Corner& c : cell_) reach2 = std::max(reach2, c.x * c.x + c.y * c.y);
      }
    }
    // 3. A corner between two bisector edges is a Delaunay triangle (point, a, b). Start after a
    //    box edge, if any, so that the triangles of an open fan come out consecutively.
    const std::size_t m = cell_.size();
    std::size_t start = 0;
    bool open = false;
    for (std::size_t c = 0; c < m; ++c)
      if (cell_[c].label < 0) open = true, start = (c + 1) % m;
    for (std::size_t s = 0; s < m; ++s) {
      const std::size_t c = (start + s) % m;
      const std::int32_t a = cell_[(c + m - 1) % m].label, bb = cell_[c].label;
      if (a >= 0 && bb >= 0 && a != bb) out.push_back({nb.indices[b + static_cast<std::uint32_t>(a)], nb.indices[b + static_cast<std::uint32_t>(bb)]});
    }
    return !open;
  }

 private:
  // Sutherland-Hodgman against one half-plane; returns whether the cell changed.
  bool clip(double qx, double qy, double half, double tol, std::int32_t label) {
    const std::size_t m = cell_.size();
    side_.resize(m);
    bool any_out = false;
    for (std::size_t c = 0; c < m; ++c) {
      side_[c] = cell_[c].x * qx + cell_[c].y * qy - half;
      any_out = any_out || side_[c] > tol;
    }
    if (!any_out) return false;
    next_.clear();
    for (std::size_t c = 0; c < m; ++c) {
      const std::size_t d = (c + 1) % m;
      const bool in_c = side_[c] <= tol, in_d = side_[d] <= tol;
      if (in_c) next_.push_back(cell_[c]);
      if (in_c != in_d) {
        const double t = side_[c] / (side_[c] - side_[d]);
        const Corner z{cell_[c].x + t * (cell_[d].x - cell_[c].x), cell_[c].y + t * (cell_[d].y - cell_[c].y),
                       in_c ? label : cell_[c].label};
        next_.push_back(z);
      }
    }
    cell_.swap(next_);
    return true;
  }

  std::vector<std::array<double, 2>> proj_;
  std::vector<Corner> cell_, next_;
  std::vector<double> side_;
};

}  // namespace

Fans compute_fans(const std::vector<Vec3f>& positions, const Neighborhoods& nb, const LocalFrames& frames,
                  FanReport* report) {
  const std::size_t n = positions.size();
  Fans fans;
  fans.offsets.assign(n + 1, 0);
  // Chunks of consecutive points handed out dynamically (no thread waits for a slowed one), joined
  // in point order: thread-count independent.
  constexpr std::size_t kChunk = 2048;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::vector<std::array<std::uint32_t, 2>>> blocks(chunks);
  std::size_t open = 0, empty = 0, duplicates = 0;
#pragma omp parallel reduction(+ : open, empty, duplicates)
  {
    CellClipper clipper;
#pragma omp for schedule(dynamic)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(chunks); ++c) {
      auto& out = blocks[static_cast<std::size_t>(c)];
      out.reserve(6 * kChunk + 64);  // ~6 triangles a point (a closed fan of a regular sampling)
      const std::size_t first = static_cast<std::size_t>(c) * kChunk, last = std::min(n, first + kChunk);
      for (std::size_t i = first; i < last; ++i) {
        const std::size_t before = out.size();
        const bool closed = clipper.fan(i, positions, nb, frames, out, duplicates);
        const std::size_t count = out.size() - before;
        fans.offsets[i + 1] = static_cast<std::uint32_t>(count);
        if (count == 0) ++empty;
        else if (!closed) ++open;
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) fans.offsets[i + 1] += fans.offsets[i];
  fans.triangles.reserve(fans.offsets[n]);
  for (auto& blk : blocks) {
    fans.triangles.insert(fans.triangles.end(), blk.begin(), blk.end());
    std::vector<std::array<std::uint32_t, 2>>().swap(blk);
  }
  if (report) report->open = open, report->empty = empty, report->duplicates = duplicates;
  return fans;
}

}  // namespace qf
