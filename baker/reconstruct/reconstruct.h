// Surface reconstruction of a point set: the peer a scan user would pick beside the impostors
// (reconstruct, then simplify into mesh LODs). CGAL's advancing-front reconstruction (Cohen-Steiner
// and Da 2004), chosen because its vertices are the input points themselves: colours carry over
// unchanged, nothing is smoothed away or invented past the scan's edges (Poisson closes every
// surface, a facade into a blob), and it needs no normals.
#pragma once

#include <cstddef>

#include "core/types.h"

namespace qf {

struct ReconstructOptions {
  // The reconstruction runs on at most this many points: an even subsample (every k-th point of
  // the Morton order). Its cost grows faster than the points: CGAL's building.ply took 8.5 s CPU
  // from all of its 100k points, 1.4 s from 50k, 0.3 s from 25k (the rest of its bake: 7 s).
  // The LODs a user picks beside impostors are the coarse ones (the finest, S0, is a quarter of the
  // reconstructed triangles: ~25k from 50k points).
  std::size_t max_points = 50000;
};

struct Reconstruction {
  TriangleMesh mesh;  // vertices: the points used, with their colours; no normals (left to the writer)
  std::size_t points_used = 0;
};

// The reconstructed surface of `points`. Deterministic (same points, same mesh, whatever ran before
// and on whichever thread). Throws std::invalid_argument when fewer than 4 points, or no triangle,
// remain (all on one line; a flat grid reconstructs), or when CGAL fails on them.
Reconstruction reconstruct_surface(const PointSet& points, const ReconstructOptions& options = {});

}  // namespace qf
