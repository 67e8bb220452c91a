// Point neighbourhoods (paper 2.1): k nearest neighbours, optionally widened to the feature-size
// ball B_eps(x), found with FLANN's kd-tree and stored flat. This header is FLANN-free; FLANN stays
// inside neighborhoods.cpp.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/types.h"

namespace qf {

// Neighbour lists of n points, flat: the neighbours of point i are indices[offsets[i] ..
// offsets[i+1]), sorted by increasing distance, ties by increasing index, the point itself
// excluded. distances holds the Euclidean distances (world units) alongside.
struct Neighborhoods {
  std::vector<std::uint32_t> offsets;  // n + 1 entries
  std::vector<std::uint32_t> indices;
  std::vector<float> distances;

  std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t count(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
};

struct NeighborhoodOptions {
  int k = 50;            // neighbours per point; the k_min of the ball mode (paper 2.1: 50..100)
  float epsilon = 0.0f;  // feature size (world units); 0 = off. When the k-th neighbour is closer
                         // than epsilon, every further point inside B_eps(x) is added too (paper 2.1)
  int max_neighbors = 200;  // cap on the ball's size, so memory stays bounded (~1.6 KB per point)
};

struct NeighborhoodReport {
  std::size_t widened = 0;  // points whose ball added neighbours beyond k
  std::size_t capped = 0;   // points whose ball held more than max_neighbors
};

// Neighbourhoods of every point. Uses every core; the result does not depend on the thread count.
// Coincident points are neighbours at distance 0. Sets of at most k points give every point the
// n - 1 others.
Neighborhoods compute_neighborhoods(const std::vector<Vec3f>& positions, const NeighborhoodOptions& options = {},
                                    NeighborhoodReport* report = nullptr);

// The min(k, n-1) nearest neighbours of every point (compute_neighborhoods without the ball).
Neighborhoods k_nearest(const std::vector<Vec3f>& positions, int k);

// The nearest of a fixed set of points to any query point, on the same kd-tree: the out-of-core
// bake links each of its points to the subsample (pipeline/out_of_core.cpp). Exact, ties by lower
// index, so answers do not depend on the threads asking (queries are const and may run at once).
class NearestPoints {
 public:
  explicit NearestPoints(const std::vector<Vec3f>& points);
  ~NearestPoints();
  NearestPoints(const NearestPoints&) = delete;
  NearestPoints& operator=(const NearestPoints&) = delete;

  // The min(k, size) nearest points of each of `queries`: indices into the set and squared
  // distances, nearest first, at index[q * k + j] and d2[q * k + j]; returns how many a query got.
  // Only points within squared distance `max_d2` are looked for: a query with fewer there gets
  // d2 = infinity (and the index of its nearest, else 0) in the slots past them. The bound is what
  // keeps a query far from every point cheap: unbounded, a kd-tree visits most of its nodes for it.
  int nearest(const Vec3f* queries, std::size_t count, int k, std::uint32_t* index, float* d2,
              float max_d2 = INFINITY) const;

 private:
  struct Tree;
  std::vector<float> cloud_;  // xyz interleaved
  std::unique_ptr<Tree> tree_;
};

struct OutlierOptions {
  int k = 8;            // the neighbours a point's spacing is the mean distance to
  float factor = 0.0f;  // a point is an outlier past factor x the median spacing; 0 = none are
};

// The outliers of a point set (method.md stage 0): points whose spacing (mean distance to their k
// nearest neighbours) is more than `factor` times the median spacing of the set, such as a
// scanner's mixed pixels and strays, far from any surface. A global, robust rule: the classic
// statistical one (mean + m standard deviations, PCL's StatisticalOutlierRemoval) drops the
// sparse tail of every clean set (0.37% of a uniformly sampled torus at m = 3), and a local one
// (spacing against the neighbours' spacing) misses strays that lie among other strays. Its limit:
// a clean set whose spacing varies more than `factor`-fold (a terrestrial scan's far points)
// loses its sparsest parts; factor 0 keeps everything. Returns one flag per point (1: outlier);
// none with factor 0, at most k points, or a median spacing of 0. Every core; the same at any thread count.
// `limit`, when given, gets the spacing past which a point went (factor x the median; infinity
// where none could).
std::vector<char> find_outliers(const std::vector<Vec3f>& positions, const OutlierOptions& options, float* limit = nullptr);

// find_outliers, then those points erased from every per-point array (core/types.h
// erase_points); returns how many went.
std::size_t drop_outliers(PointSet& points, const OutlierOptions& options, float* limit = nullptr);

struct RadiusEstimateOptions {
  int k = 6;  // the radius reaches the k-th nearest neighbour: about the first ring of a sampling
};

// Splat radius from local spacing (method.md stage 0): the distance to the k-th nearest neighbour
// (at non-zero distance). Discs that large cover the surface: a hexagonal sampling with spacing h
// gets r = h (it needs 0.58 h), a uniform random one leaves ~e^-6 = 0.25% of the area uncovered;
// the mean distance to the 6 nearest (~1.0/sqrt(density)) left ~4% as holes in the textures.
// Points whose neighbours all coincide with them get the
// median of the other estimates; a set with no spacing at all (one point, or all coincident)
// gets 1% of its bounding-box diagonal, or 1 if that is 0. Fills `points.radii` where it is
// empty; where it is present, only entries equal to 0 are replaced. Returns how many were set.
std::size_t estimate_radii(PointSet& points, const RadiusEstimateOptions& options = {});

}  // namespace qf
