// Neighbourhood search (PCL KdTreeFLANN) and spacing-based radius estimation (paper 2.1).
#include "analysis/neighborhoods.h"

#include <omp.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>

namespace qf {
namespace {

using Candidate = std::pair<float, std::uint32_t>;  // squared distance, input index: sorts by distance, then index

// Extra results asked of the kd-tree beyond k, so that points tied with the k-th neighbour are
// seen and the lowest indices win whatever order the tree returns them in (costs ~5%).
constexpr int kTieSlack = 8;

// Points sorted along a Morton (Z-order) curve over their bounding box, ties by index. The tree is
// built on this order and queried in it, so that consecutive queries touch nearby memory.
std::vector<std::uint32_t> morton_order(const std::vector<Vec3f>& positions) {
  Bounds box;
  for (const Vec3f& p : positions) box.add(p);
  const Vec3f size = box.size();
  const float extent = std::max({size.x, size.y, size.z, 1e-30f});
  auto spread = [](std::uint64_t v) {  // 21 bits -> every third bit of 63
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    std::uint64_t c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = static_cast<std::uint64_t>(std::clamp((positions[i][a] - box.min[a]) / extent, 0.0f, 1.0f) * 2097151.0f);
    keys[i] = {spread(c[0]) | spread(c[1]) << 1 | spread(c[2]) << 2, static_cast<std::uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> order(positions.size());
  for (std::size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].second;
  return order;
}

class Searcher {
 public:
  // order[s] = the input index of the s-th point of the tree's cloud.
  Searcher(const std::vector<Vec3f>& positions, const std::vector<std::uint32_t>& order)
      : cloud_(new pcl::PointCloud<pcl::PointXYZ>), order_(&order) {
    cloud_->resize(positions.size());
    for (std::size_t s = 0; s < order.size(); ++s) {
      const Vec3f& p = positions[order[s]];
      (*cloud_)[s] = pcl::PointXYZ(p.x, p.y, p.z);
    }
    tree_.setSortedResults(false);  // collect() sorts, with index tie-breaking
    tree_.setInputCloud(cloud_);
  }

  // The neighbours of the s-th point of the cloud (itself excluded), as (squared distance, input
  // index), sorted, into `out`.
  void query(std::size_t s, int k, float epsilon, int max_neighbors, std::vector<Candidate>& out, bool& widened,
             bool& capped) {
    const pcl::PointXYZ& p = (*cloud_)[s];
    const int n = static_cast<int>(cloud_->size());
    widened = capped = false;
    const int want = std::min(k + 1 + kTieSlack, n);
    tree_.nearestKSearch(p, want, found_, sq_);
    collect(s, out);
    // All retrieved points tie with the k-th one: fetch every point at that distance.
    if (static_cast<int>(out.size()) > k && want < n && out.back().first == out[static_cast<std::size_t>(k) - 1].first) {
      tree_.radiusSearch(p, std::sqrt(out.back().first) * (1 + 1e-6f), found_, sq_);
      collect(s, out);
    }
    // Ball mode (paper 2.1): the k-th neighbour lies inside B_eps, so take all of B_eps.
    if (epsilon > 0 && static_cast<int>(out.size()) >= k && out[static_cast<std::size_t>(k) - 1].first < epsilon * epsilon) {
      tree_.radiusSearch(p, epsilon, found_, sq_);
      collect(s, out);
      widened = static_cast<int>(out.size()) > k;
      if (static_cast<int>(out.size()) > max_neighbors) {
        capped = true;
        out.resize(static_cast<std::size_t>(max_neighbors));
      }
      return;
    }
    if (static_cast<int>(out.size()) > k) out.resize(static_cast<std::size_t>(k));
  }

 private:
  void collect(std::size_t s, std::vector<Candidate>& out) {
    out.clear();
    for (std::size_t r = 0; r < found_.size(); ++r)
      if (static_cast<std::size_t>(found_[r]) != s) out.push_back({sq_[r], (*order_)[static_cast<std::size_t>(found_[r])]});
    std::sort(out.begin(), out.end());
  }

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_;
  const std::vector<std::uint32_t>* order_;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree_;
  pcl::Indices found_;
  std::vector<float> sq_;
};

}  // namespace

Neighborhoods compute_neighborhoods(const std::vector<Vec3f>& positions, const NeighborhoodOptions& options,
                                    NeighborhoodReport* report) {
  const std::size_t n = positions.size();
  Neighborhoods nb;
  nb.offsets.assign(n + 1, 0);
  const int k = std::max(1, options.k);
  const int max_neighbors = std::max(options.max_neighbors, k);
  if (n < 2) return nb;

  const std::vector<std::uint32_t> order = morton_order(positions);
  const Searcher shared(positions, order);

  if (!(options.epsilon > 0)) {
    // Plain k nearest: every point has exactly min(k, n-1) neighbours, so each query writes its
    // own slots of the final arrays (no intermediate copies: fresh pages are costly here).
    const std::size_t kk = std::min<std::size_t>(static_cast<std::size_t>(k), n - 1);
    for (std::size_t i = 0; i <= n; ++i) nb.offsets[i] = static_cast<std::uint32_t>(i * kk);
    nb.indices.resize(n * kk);
    nb.distances.resize(n * kk);
#pragma omp parallel
    {
      Searcher search = shared;  // FLANN's query scratch is per searcher: one copy per thread
      std::vector<Candidate> found;
      bool w = false, c = false;
#pragma omp for schedule(static)
      for (std::ptrdiff_t ss = 0; ss < static_cast<std::ptrdiff_t>(n); ++ss) {
        search.query(static_cast<std::size_t>(ss), k, 0.0f, max_neighbors, found, w, c);
        const std::size_t base = order[static_cast<std::size_t>(ss)] * kk;
        for (std::size_t r = 0; r < kk; ++r) {
          nb.indices[base + r] = found[r].second;
          nb.distances[base + r] = std::sqrt(found[r].first);
        }
      }
    }
    return nb;
  }

  // Ball mode: counts vary. Each thread takes one contiguous block of the Morton order (static
  // schedule) into its own lists, which are then scattered to input order; the result is the same
  // for any thread count.
  std::vector<std::vector<std::uint32_t>> block_indices;
  std::vector<std::vector<float>> block_distances;
  std::vector<std::size_t> block_start;
  std::size_t widened = 0, capped = 0;
#pragma omp parallel reduction(+ : widened, capped)
  {
#pragma omp single
    {
      block_indices.resize(static_cast<std::size_t>(omp_get_num_threads()));
      block_distances.resize(block_indices.size());
      block_start.assign(block_indices.size(), n);
    }
    Searcher search = shared;
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    std::vector<Candidate> found;
#pragma omp for schedule(static)
    for (std::ptrdiff_t ss = 0; ss < static_cast<std::ptrdiff_t>(n); ++ss) {
      const auto s = static_cast<std::size_t>(ss);
      block_start[t] = std::min(block_start[t], s);
      bool w = false, c = false;
      search.query(s, k, options.epsilon, max_neighbors, found, w, c);
      widened += w, capped += c;
      nb.offsets[order[s] + 1] = static_cast<std::uint32_t>(found.size());
      for (const Candidate& f : found) {
        block_indices[t].push_back(f.second);
        block_distances[t].push_back(std::sqrt(f.first));
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) nb.offsets[i + 1] += nb.offsets[i];
  nb.indices.resize(nb.offsets[n]);
  nb.distances.resize(nb.offsets[n]);
  for (std::size_t t = 0; t < block_indices.size(); ++t) {
    std::size_t r = 0;
    for (std::size_t s = block_start[t]; r < block_indices[t].size(); ++s) {
      const std::uint32_t i = order[s];
      for (std::uint32_t dst = nb.offsets[i]; dst < nb.offsets[i + 1]; ++dst, ++r) {
        nb.indices[dst] = block_indices[t][r];
        nb.distances[dst] = block_distances[t][r];
      }
    }
    std::vector<std::uint32_t>().swap(block_indices[t]);
    std::vector<float>().swap(block_distances[t]);
  }
  if (report) report->widened = widened, report->capped = capped;
  return nb;
}

Neighborhoods k_nearest(const std::vector<Vec3f>& positions, int k) {
  NeighborhoodOptions o;
  o.k = k;
  return compute_neighborhoods(positions, o);
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
