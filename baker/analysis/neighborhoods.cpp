// Neighbourhood search (FLANN's kd-tree, called directly) and spacing-based radius estimation
// (paper 2.1).
#include "analysis/neighborhoods.h"

#include "core/memory.h"

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <flann/util/matrix.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace qf {
namespace {

using Candidate = std::pair<float, std::uint32_t>;  // squared distance, input index: sorts by distance, then index

// Extra results asked of the kd-tree beyond k, so that points tied with the k-th neighbour are
// seen and the lowest indices win whatever order the tree returns them in. One suffices for exact
// answers: when the extra one lies farther than the k-th, the exact search has returned every point
// at the k-th distance; when it ties, query_block fetches them all with a ball search. More extras
// only make the ball rarer: 8 cost ~15% of the search on bunny00's vertices (37.7k points; the
// result set's insertion is O(k)) and saved nothing on depth-peeled samples, where ties abound
// (bunny00 and fandisk at LDI 256-300: same time, same neighbourhoods).
constexpr int kTieSlack = 1;

// The kd-tree is built on the points in Morton order (core/types.h morton_order) and queried in
// it, so that consecutive queries touch nearby memory.

// Exact neighbour queries on FLANN's single kd-tree, the index behind PCL's KdTreeFLANN, called
// directly rather than through PCL: PCL's wrapper answers one point per call and allocates on each
// (6.7 us per k = 59 query on 100k points); asking the same FLANN tree for a block of points at a
// time takes 3.8 us. PCL is left only as the CMake package that finds FLANN (CMakeLists.txt).
class Searcher {
 public:
  // cloud: the points in Morton order, xyz interleaved; order[s] = input index of cloud point s.
  Searcher(const std::vector<float>& cloud, const std::vector<std::uint32_t>& order)
      : order_(order),
        data_(const_cast<float*>(cloud.data()), order.size(), 3),
        tree_(data_, flann::KDTreeSingleIndexParams(15)) {
    tree_.buildIndex();
  }

  // Neighbours of cloud points [first, first + count) into `lists` (one per point, (squared
  // distance, input index), sorted, the point itself excluded): the k nearest, or when the k-th
  // lies inside B_epsilon, all of B_epsilon (at most max_neighbors).
  struct Scratch {
    std::vector<std::size_t> found;
    std::vector<float> sq;
    std::vector<std::vector<Candidate>> lists;
  };

  void query_block(std::size_t first, std::size_t count, int k, float epsilon, int max_neighbors, Scratch& sc,
                   std::size_t& widened, std::size_t& capped) const {
    const std::size_t n = order_.size();
    const int want = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(k) + 1 + kTieSlack, n));
    sc.found.resize(count * static_cast<std::size_t>(want));
    sc.sq.resize(sc.found.size());
    flann::Matrix<float> queries(data_.ptr() + 3 * first, count, 3);
    flann::Matrix<std::size_t> found(sc.found.data(), count, static_cast<std::size_t>(want));
    flann::Matrix<float> sq(sc.sq.data(), count, static_cast<std::size_t>(want));
    tree_.knnSearch(queries, found, sq, static_cast<std::size_t>(want), flann::SearchParams(-1, 0.0f, false));
    sc.lists.resize(count);
    for (std::size_t q = 0; q < count; ++q) {
      std::vector<Candidate>& out = sc.lists[q];
      const std::size_t s = first + q;
      collect(s, sc.found.data() + q * want, sc.sq.data() + q * want, static_cast<std::size_t>(want), out);
      // All retrieved points tie with the k-th one: fetch every point at that distance.
      if (static_cast<int>(out.size()) > k && static_cast<std::size_t>(want) < n &&
          out.back().first == out[static_cast<std::size_t>(k) - 1].first)
        ball(s, out.back().first * (1 + 1e-6f), out);
      // Ball mode (paper 2.1): the k-th neighbour lies inside B_eps, so take all of B_eps.
      if (epsilon > 0 && static_cast<int>(out.size()) >= k &&
          out[static_cast<std::size_t>(k) - 1].first < epsilon * epsilon) {
        ball(s, epsilon * epsilon, out);
        widened += static_cast<int>(out.size()) > k;
        if (static_cast<int>(out.size()) > max_neighbors) {
          ++capped;
          out.resize(static_cast<std::size_t>(max_neighbors));
        }
      } else if (static_cast<int>(out.size()) > k) {
        out.resize(static_cast<std::size_t>(k));
      }
    }
  }

 private:
  // Every point within squared distance r2 of cloud point s (FLANN's radius is squared for L2).
  void ball(std::size_t s, float r2, std::vector<Candidate>& out) const {
    std::vector<std::vector<std::size_t>> idx;
    std::vector<std::vector<float>> dist;
    flann::Matrix<float> query(data_.ptr() + 3 * s, 1, 3);
    tree_.radiusSearch(query, idx, dist, r2, flann::SearchParams(-1, 0.0f, false));
    collect(s, idx[0].data(), dist[0].data(), idx[0].size(), out);
  }

  void collect(std::size_t s, const std::size_t* idx, const float* sq, std::size_t m, std::vector<Candidate>& out) const {
    out.clear();
    for (std::size_t r = 0; r < m; ++r)
      if (idx[r] != s) out.push_back({sq[r], order_[idx[r]]});
    // The k-nearest answers come sorted by distance (FLANN's result set is an insertion sort), so
    // only ties can be out of index order, and most lists need no sort (~7% of the bunny's search).
    if (!std::is_sorted(out.begin(), out.end())) std::sort(out.begin(), out.end());
  }

  const std::vector<std::uint32_t>& order_;
  flann::Matrix<float> data_;
  // FLANN's search methods are const but not marked so; queries never modify the tree.
  mutable flann::KDTreeSingleIndex<flann::L2_Simple<float>> tree_;
};

// Queries go in blocks of consecutive points along the Morton curve; blocks are handed out to the
// threads dynamically (a thread slowed by the machine's other jobs does not hold the other up),
// and each block's answer depends only on the block, so any thread count gives the same.
constexpr std::size_t kBlock = 512;

// The points in Morton order, xyz interleaved: the Searcher's cloud.
std::vector<float> morton_cloud(const std::vector<Vec3f>& positions, const std::vector<std::uint32_t>& order) {
  std::vector<float> cloud(3 * positions.size());
  for (std::size_t s = 0; s < positions.size(); ++s)
    for (int a = 0; a < 3; ++a) cloud[3 * s + static_cast<std::size_t>(a)] = positions[order[s]][a];
  return cloud;
}

// Every cloud point's k nearest, block by block of the Morton order on every core:
// visit(first, count, lists) for each block, concurrently for different blocks.
template <class Visit>
void for_each_nearest_block(const Searcher& search, std::size_t n, int k, int max_neighbors, Visit&& visit) {
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
#pragma omp parallel
  {
    Searcher::Scratch sc;
    std::size_t unused = 0;
#pragma omp for schedule(dynamic)
    for (std::ptrdiff_t b = 0; b < static_cast<std::ptrdiff_t>(blocks); ++b) {
      const std::size_t first = static_cast<std::size_t>(b) * kBlock, count = std::min(kBlock, n - first);
      search.query_block(first, count, k, 0.0f, max_neighbors, sc, unused, unused);
      visit(first, count, sc.lists);
    }
  }
}

// Plain k nearest: every point has exactly min(k, n-1) neighbours, so each point's slots in the
// final arrays are known and written directly (fresh pages are costly here).
void k_nearest_lists(const Searcher& search, const std::vector<std::uint32_t>& order, int k, int max_neighbors, Neighborhoods& nb) {
  const std::size_t n = order.size();
  const std::size_t kk = std::min<std::size_t>(static_cast<std::size_t>(k), n - 1);
  for (std::size_t i = 0; i <= n; ++i) nb.offsets[i] = static_cast<std::uint32_t>(i * kk);
  reserve_huge(nb.indices, n * kk);
  reserve_huge(nb.distances, n * kk);
  nb.indices.resize(n * kk);
  nb.distances.resize(n * kk);
  for_each_nearest_block(search, n, k, max_neighbors, [&](std::size_t first, std::size_t count, const std::vector<std::vector<Candidate>>& lists) {
    for (std::size_t q = 0; q < count; ++q) {
      const std::size_t base = order[first + q] * kk;
      for (std::size_t r = 0; r < kk; ++r) {
        nb.indices[base + r] = lists[q][r].second;
        nb.distances[base + r] = std::sqrt(lists[q][r].first);
      }
    }
  });
}

// Ball mode's answers, per block of the Morton order: the lists one after the other, and their sizes.
struct BlockAnswers {
  std::vector<std::vector<Candidate>> lists;
  std::vector<std::vector<std::uint32_t>> counts;
};

// Ball mode, first pass: counts vary, so each block keeps its answers until all counts are known.
BlockAnswers query_balls(const Searcher& search, std::size_t n, int k, float epsilon, int max_neighbors,
                         NeighborhoodReport& tally) {
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  BlockAnswers out{std::vector<std::vector<Candidate>>(blocks), std::vector<std::vector<std::uint32_t>>(blocks)};
  std::size_t widened = 0, capped = 0;
#pragma omp parallel reduction(+ : widened, capped)
  {
    Searcher::Scratch sc;
#pragma omp for schedule(dynamic)
    for (std::ptrdiff_t b = 0; b < static_cast<std::ptrdiff_t>(blocks); ++b) {
      const auto bi = static_cast<std::size_t>(b);
      const std::size_t first = bi * kBlock, count = std::min(kBlock, n - first);
      search.query_block(first, count, k, epsilon, max_neighbors, sc, widened, capped);
      for (std::size_t q = 0; q < count; ++q) {
        out.counts[bi].push_back(static_cast<std::uint32_t>(sc.lists[q].size()));
        out.lists[bi].insert(out.lists[bi].end(), sc.lists[q].begin(), sc.lists[q].end());
      }
    }
  }
  tally.widened = widened, tally.capped = capped;
  return out;
}

// Ball mode, second pass: the blocks' answers scattered to input order (each block freed once done).
void scatter_balls(BlockAnswers& answers, const std::vector<std::uint32_t>& order, Neighborhoods& nb) {
  const std::size_t n = order.size(), blocks = answers.lists.size();
  for (std::size_t b = 0; b < blocks; ++b)
    for (std::size_t q = 0; q < answers.counts[b].size(); ++q) nb.offsets[order[b * kBlock + q] + 1] = answers.counts[b][q];
  for (std::size_t i = 0; i < n; ++i) nb.offsets[i + 1] += nb.offsets[i];
  reserve_huge(nb.indices, nb.offsets[n]);
  reserve_huge(nb.distances, nb.offsets[n]);
  nb.indices.resize(nb.offsets[n]);
  nb.distances.resize(nb.offsets[n]);
  for (std::size_t b = 0; b < blocks; ++b) {
    std::size_t r = 0;
    for (std::size_t q = 0; q < answers.counts[b].size(); ++q) {
      const std::uint32_t i = order[b * kBlock + q];
      for (std::uint32_t dst = nb.offsets[i]; dst < nb.offsets[i + 1]; ++dst, ++r) {
        nb.indices[dst] = answers.lists[b][r].second;
        nb.distances[dst] = std::sqrt(answers.lists[b][r].first);
      }
    }
    std::vector<Candidate>().swap(answers.lists[b]);
  }
}

}  // namespace

// Every point's k nearest neighbours, or with epsilon > 0 and the k-th inside B_eps, all of B_eps
// (at most max_neighbors): a kd-tree over the points in Morton order, queried in blocks on every
// core. Fewer than 2 points: empty lists. Only ball mode fills the report.
Neighborhoods compute_neighborhoods(const std::vector<Vec3f>& positions, const NeighborhoodOptions& options,
                                    NeighborhoodReport* report) {
  const std::size_t n = positions.size();
  Neighborhoods nb;
  nb.offsets.assign(n + 1, 0);
  const int k = std::max(1, options.k);
  const int max_neighbors = std::max(options.max_neighbors, k);
  if (n < 2) return nb;
  const std::vector<std::uint32_t> order = morton_order(positions);
  const std::vector<float> cloud = morton_cloud(positions, order);
  const Searcher search(cloud, order);
  if (!(options.epsilon > 0)) {
    k_nearest_lists(search, order, k, max_neighbors, nb);
    return nb;
  }
  NeighborhoodReport tally;
  BlockAnswers answers = query_balls(search, n, k, options.epsilon, max_neighbors, tally);
  scatter_balls(answers, order, nb);
  if (report) report->widened = tally.widened, report->capped = tally.capped;
  return nb;
}

Neighborhoods k_nearest(const std::vector<Vec3f>& positions, int k) {
  NeighborhoodOptions o;
  o.k = k;
  return compute_neighborhoods(positions, o);
}

struct NearestPoints::Tree {
  flann::Matrix<float> data;
  // FLANN's search methods are const but not marked so; queries never modify the tree.
  mutable flann::KDTreeSingleIndex<flann::L2_Simple<float>> index;
  explicit Tree(std::vector<float>& cloud) : data(cloud.data(), cloud.size() / 3, 3), index(data, flann::KDTreeSingleIndexParams(15)) {
    index.buildIndex();
  }
};

NearestPoints::NearestPoints(const std::vector<Vec3f>& points) {
  if (points.empty()) throw std::invalid_argument("NearestPoints: no points");
  cloud_.reserve(3 * points.size());
  for (Vec3f p : points) cloud_.insert(cloud_.end(), {p.x, p.y, p.z});
  tree_ = std::make_unique<Tree>(cloud_);
}

NearestPoints::~NearestPoints() = default;

int NearestPoints::nearest(const Vec3f* queries, std::size_t count, int k, std::uint32_t* index, float* d2, float max_d2) const {
  const std::size_t n = cloud_.size() / 3;
  const int got = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(k), n));
  // One more than asked (kTieSlack): where it ties with the last, a ball fetches every tie.
  const int want = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(got + kTieSlack), n));
  std::vector<float> q(3 * count);
  for (std::size_t i = 0; i < count; ++i) q[3 * i] = queries[i].x, q[3 * i + 1] = queries[i].y, q[3 * i + 2] = queries[i].z;
  std::vector<std::size_t> found(count * static_cast<std::size_t>(want));
  std::vector<float> sq(found.size());
  flann::Matrix<float> qm(q.data(), count, 3);
  flann::Matrix<std::size_t> fm(found.data(), count, static_cast<std::size_t>(want));
  flann::Matrix<float> sm(sq.data(), count, static_cast<std::size_t>(want));
  if (std::isinf(max_d2)) {
    tree_->index.knnSearch(qm, fm, sm, static_cast<std::size_t>(want), flann::SearchParams(-1, 0.0f, false));
  } else {
    // The `want` nearest within the bound (FLANN's radius is a squared distance for L2); the slot
    // after the last found holds index -1.
    flann::SearchParams bounded(-1, 0.0f, false);
    bounded.max_neighbors = want;
    tree_->index.radiusSearch(qm, fm, sm, max_d2, bounded);
  }
  std::vector<Candidate> list;
  for (std::size_t i = 0; i < count; ++i) {
    list.clear();
    for (std::size_t r = 0; r < static_cast<std::size_t>(want) && found[i * want + r] != static_cast<std::size_t>(-1); ++r)
      list.push_back({sq[i * want + r], static_cast<std::uint32_t>(found[i * want + r])});
    std::sort(list.begin(), list.end());
    if (list.size() == static_cast<std::size_t>(want) && want > got &&
        list[static_cast<std::size_t>(want) - 1].first == list[static_cast<std::size_t>(got) - 1].first) {
      std::vector<std::vector<std::size_t>> idx;
      std::vector<std::vector<float>> dist;
      flann::Matrix<float> one(q.data() + 3 * i, 1, 3);
      tree_->index.radiusSearch(one, idx, dist, list[static_cast<std::size_t>(got) - 1].first * (1 + 1e-6f), flann::SearchParams(-1, 0.0f, false));
      list.clear();
      for (std::size_t r = 0; r < idx[0].size(); ++r) list.push_back({dist[0][r], static_cast<std::uint32_t>(idx[0][r])});
      std::sort(list.begin(), list.end());
    }
    for (int j = 0; j < got; ++j) {
      const auto at = static_cast<std::size_t>(j);
      const bool in = at < list.size();
      index[i * static_cast<std::size_t>(k) + at] = in ? list[at].second : list.empty() ? 0 : list[0].second;
      d2[i * static_cast<std::size_t>(k) + at] = in ? list[at].first : INFINITY;
    }
  }
  return got;
}

std::vector<char> find_outliers(const std::vector<Vec3f>& positions, const OutlierOptions& options, float* limit_out) {
  const std::size_t n = positions.size();
  if (limit_out) *limit_out = INFINITY;
  std::vector<char> outlier(n, 0);
  if (!(options.factor > 0) || options.k < 1 || n <= static_cast<std::size_t>(options.k)) return outlier;
  // 1. Every point's spacing, from block queries on the kd-tree (no neighbour lists are kept: at
  //    100M points they would take 6.4 GB).
  std::vector<float> spacing(n);
  {
    const std::vector<std::uint32_t> order = morton_order(positions);
    const std::vector<float> cloud = morton_cloud(positions, order);
    const Searcher search(cloud, order);
    for_each_nearest_block(search, n, options.k, options.k, [&](std::size_t first, std::size_t count, const std::vector<std::vector<Candidate>>& lists) {
      for (std::size_t q = 0; q < count; ++q) {
        double sum = 0;  // nearest first: the same sum whatever the thread
        for (const Candidate& c : lists[q]) sum += std::sqrt(double(c.first));
        spacing[order[first + q]] = static_cast<float>(sum / double(lists[q].size()));
      }
    });
  }
  // 2. The rule, against the median spacing.
  std::vector<float> sorted = spacing;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2), sorted.end());
  if (!(sorted[n / 2] > 0)) return std::vector<char>(n, 0);  // most points coincide: no scale to judge by
  const double limit = double(options.factor) * double(sorted[n / 2]);
  if (limit_out) *limit_out = static_cast<float>(limit);
  for (std::size_t i = 0; i < n; ++i) outlier[i] = double(spacing[i]) > limit;
  return outlier;
}

std::size_t drop_outliers(PointSet& points, const OutlierOptions& options, float* limit) {
  const std::vector<char> drop = find_outliers(points.positions, options, limit);
  const auto dropped = static_cast<std::size_t>(std::count(drop.begin(), drop.end(), 1));
  if (dropped) erase_points(points, drop);
  return dropped;
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
    // The k-th neighbour at non-zero distance (the lists are sorted; coincident points come first).
    float reach = 0;
    int used = 0;
    for (std::uint32_t r = nb.offsets[i]; r < nb.offsets[i + 1]; ++r)
      if (nb.distances[r] > 0) reach = nb.distances[r], ++used;
    if (used > 0) {
      estimate[i] = reach;
      positive.push_back(reach);
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
