// Local Delaunay fans (paper 2.2): each point's neighbours projected onto its tangent plane, and
// the triangles of their 2D Delaunay triangulation that touch the point (its 1-ring).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "analysis/local_frames.h"
#include "analysis/neighborhoods.h"

namespace qf {

// Fans of n points, flat: the fan of point i is triangles[offsets[i] .. offsets[i+1]); a triangle
// {a, b} stands for (i, a, b), counter-clockwise around the point's normal, consecutive triangles
// sharing an edge. A fan is closed (a full ring) for interior points and open at a boundary.
struct Fans {
  std::vector<std::uint32_t> offsets;                 // n + 1 entries
  std::vector<std::array<std::uint32_t, 2>> triangles;

  std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t count(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
};

struct FanReport {
  std::size_t open = 0;        // fans that do not close around their point (surface boundary)
  std::size_t empty = 0;       // points with no triangle at all (isolated, or all neighbours collinear)
  std::size_t duplicates = 0;  // neighbours skipped because they project onto the point itself
};

// The Delaunay 1-ring of each point among its projected neighbours, computed exactly as the
// Voronoi cell of the point: the cell is clipped by the bisector of every neighbour; neighbours
// whose bisector bounds the final cell are the Delaunay neighbours, and each cell corner between
// two of them is a fan triangle. Same fans as a full 2D Delaunay triangulation of the projected
// neighbourhood (CGAL; tests/unit/analysis/fans_test.cpp), at a fraction of the cost. Where four
// or more projected points are cocircular the triangulation is not unique; corners closer than
// 1e-9 of the neighbourhood size are merged, which picks the triangles that avoid the diagonal
// through the point. Uses every core; the result does not depend on the thread count.
Fans compute_fans(const std::vector<Vec3f>& positions, const Neighborhoods& nb, const LocalFrames& frames,
                  FanReport* report = nullptr);

}  // namespace qf
