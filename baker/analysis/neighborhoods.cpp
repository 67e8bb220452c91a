// k-nearest-neighbour search (PCL KdTreeFLANN) and spacing-based radius estimation.
#include "analysis/neighborhoods.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace qf {

Neighborhoods k_nearest(const std::vector<Vec3f>& positions, int k) {
  const std::size_t n = positions.size();
  Neighborhoods nb;
  nb.offsets.assign(n + 1, 0);
  const int kk = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(k, 0)), n ? n - 1 : 0));
  if (n == 0 || kk == 0) return nb;

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(n);
  for (std::size_t i = 0; i < n; ++i) (*cloud)[i] = pcl::PointXYZ(positions[i].x, positions[i].y, positions[i].z);
  pcl::KdTreeFLANN<pcl::PointXYZ> tree(/*sorted=*/true);
  tree.setInputCloud(cloud);

  // Every point has exactly kk neighbours, so the layout is known before the parallel search.
  for (std::size_t i = 0; i <= n; ++i) nb.offsets[i] = static_cast<std::uint32_t>(i * static_cast<std::size_t>(kk));
  nb.indices.resize(n * static_cast<std::size_t>(kk));
  nb.distances.resize(nb.indices.size());

#pragma omp parallel
  {
    pcl::Indices found;
    std::vector<float> sq;
    std::vector<std::pair<float, std::uint32_t>> sorted;
#pragma omp for schedule(static)
    for (std::ptrdiff_t si = 0; si < static_cast<std::ptrdiff_t>(n); ++si) {
      const auto i = static_cast<std::size_t>(si);
      // Ask for one more than needed: the point itself (or a duplicate of it) is among the results.
      tree.nearestKSearch((*cloud)[i], kk + 1, found, sq);
      sorted.clear();
      for (std::size_t r = 0; r < found.size(); ++r)
        if (static_cast<std::size_t>(found[r]) != i) sorted.push_back({sq[r], static_cast<std::uint32_t>(found[r])});
      std::sort(sorted.begin(), sorted.end());  // distance, then index: independent of the search's tie order
      for (int r = 0; r < kk; ++r) {
        nb.indices[i * kk + r] = sorted[r].second;
        nb.distances[i * kk + r] = std::sqrt(sorted[r].first);
      }
    }
  }
  return nb;
}

std::size_t estimate_radii(PointSet& points, const RadiusEstimateOptions& options) {
  const std::size_t n = points.size();
  const bool fill_all = !points.has_radii();
  if (fill_all) points.radii.assign(n, 0.0f);
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < n; ++i)
    if (points.radii[i] == 0.0f) todo.push_back(i);
  if (todo.empty()) return 0;

  const Neighborhoods nb = k_nearest(points.positions, options.k);
  std::vector<float> estimate(n, 0.0f);
  std::vector<float> positive;
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0;
    int used = 0;
    for (std::uint32_t r = nb.offsets[i]; r < nb.offsets[i + 1]; ++r)
      if (nb.distances[r] > 0) sum += nb.distances[r], ++used;
    if (used > 0) {
      estimate[i] = static_cast<float>(sum / used);
      positive.push_back(estimate[i]);
    }
  }
  float fallback;
  if (!positive.empty()) {
    std::nth_element(positive.begin(), positive.begin() + static_cast<std::ptrdiff_t>(positive.size() / 2), positive.end());
    fallback = positive[positive.size() / 2];
  } else {
    const float diag = points.bounds().diagonal();
    fallback = diag > 0 ? 0.01f * diag : 1.0f;
  }
  for (std::size_t i : todo) points.radii[i] = estimate[i] > 0 ? estimate[i] : fallback;
  return todo.size();
}

}  // namespace qf
