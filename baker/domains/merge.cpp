// Greedy domain merging with additive Psi-weighted moments (thesis 3.4).
#include "domains/merge.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <map>
#include <numeric>
#include <queue>

namespace qf {
namespace {

// Psi-weighted moments of a basis function: they add up when functions are summed.
struct Moments {
  double w = 0;
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  Eigen::Matrix3d ss = Eigen::Matrix3d::Zero();
  void add(const Moments& o) { w += o.w, s += o.s, ss += o.ss; }
};

struct Plane {
  double variation;  // lambda_min / trace of the weighted covariance
  Eigen::Vector3d normal;
};

Plane plane_of(const Moments& m, const Eigen::Vector3d& origin) {
  if (!(m.w > 0)) return {1.0, Eigen::Vector3d::UnitZ()};
  // Moments were taken relative to `origin` for precision.
  const Eigen::Vector3d mean = m.s / m.w;
  const Eigen::Matrix3d cov = m.ss / m.w - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
  const double trace = ev.sum();
  (void)origin;
  return {trace > 0 ? ev(0) / trace : 0.0, eig.eigenvectors().col(0)};
}

}  // namespace

SparseMatrix merge_domains(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const MergeOptions& options,
                           MergeReport* report) {
  const auto m = static_cast<std::size_t>(psi.cols());
  // 1. Per-function moments, relative to the bounding-box centre.
  Bounds box;
  for (const Vec3f& p : positions) box.add(p);
  const Vec3f c = box.center();
  const Eigen::Vector3d origin(c.x, c.y, c.z);
  std::vector<Moments> moments(m);
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    const Vec3f p = positions[static_cast<std::size_t>(i)];
    const Eigen::Vector3d x(double(p.x) - c.x, double(p.y) - c.y, double(p.z) - c.z);
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) {
      Moments& mo = moments[static_cast<std::size_t>(it.col())];
      mo.w += it.value();
      mo.s += it.value() * x;
      mo.ss += it.value() * x * x.transpose();
    }
  }
  // 2. Pairwise overlaps of the thresholded domains.
  const Domains d = make_domains(psi, options.domains);
  std::vector<std::map<std::size_t, double>> overlap(m);  // overlap[f][g]: shared points (both directions)
  {
    // shared counts per pair, from each point's memberships
    std::vector<std::vector<std::uint32_t>> of_point(static_cast<std::size_t>(psi.rows()));
    for (std::size_t f = 0; f < d.count(); ++f)
      for (std::uint32_t r = d.offsets[f]; r < d.offsets[f + 1]; ++r) of_point[d.points[r]].push_back(static_cast<std::uint32_t>(f));
    for (const auto& list : of_point)
      for (std::size_t a = 0; a < list.size(); ++a)
        for (std::size_t b = a + 1; b < list.size(); ++b) overlap[list[a]][list[b]] += 1, overlap[list[b]][list[a]] += 1;
  }
  // 3. Greedy: the qualifying pair with the largest overlap first (ties: lowest indices).
  std::vector<std::size_t> group(m);
  std::iota(group.begin(), group.end(), std::size_t{0});
  auto find = [&](std::size_t x) {
    while (group[x] != x) x = group[x] = group[group[x]];
    return x;
  };
  struct Candidate {
    double shared;
    std::size_t a, b;
    bool operator<(const Candidate& o) const {  // max-heap on shared, then lowest (a, b)
      if (shared != o.shared) return shared < o.shared;
      return std::tie(a, b) > std::tie(o.a, o.b);
    }
  };
  std::priority_queue<Candidate> heap;
  for (std::size_t f = 0; f < m; ++f)
    for (const auto& kv : overlap[f])
      if (f < kv.first) heap.push({kv.second, f, kv.first});
  const double cos_max = std::cos(options.max_angle_degrees * 3.14159265358979323846 / 180.0);
  auto qualifies = [&](std::size_t a, std::size_t b) {
    const Plane pa = plane_of(moments[a], origin), pb = plane_of(moments[b], origin);
    return pa.variation <= options.max_variation && pb.variation <= options.max_variation &&
           std::fabs(pa.normal.dot(pb.normal)) >= cos_max;
  };
  std::size_t merges = 0;
  while (!heap.empty()) {
    const Candidate cand = heap.top();
    heap.pop();
    const std::size_t a = find(cand.a), b = find(cand.b);
    if (a == b) continue;
    const auto current = overlap[a].find(b);
    if (a != cand.a || b != cand.b || current == overlap[a].end() || current->second != cand.shared) continue;  // stale
    if (!qualifies(a, b)) continue;
    // Merge b into a (the lower index stays the representative).
    const std::size_t keep = std::min(a, b), gone = std::max(a, b);
    group[gone] = keep;
    moments[keep].add(moments[gone]);
    ++merges;
    // The merged group's overlaps with the others: sums over its members.
    for (const auto& kv : overlap[gone]) {
      if (kv.first == keep) continue;
      overlap[keep][kv.first] += kv.second;
      overlap[kv.first].erase(gone);
      overlap[kv.first][keep] = overlap[keep][kv.first];
    }
    overlap[keep].erase(gone);
    overlap[gone].clear();
    for (const auto& kv : overlap[keep]) heap.push({kv.second, std::min(keep, kv.first), std::max(keep, kv.first)});
  }
  // 4. Psi' = Psi M with groups numbered in order of their representatives.
  std::vector<std::int32_t> column(m, -1);
  std::int32_t count = 0;
  for (std::size_t f = 0; f < m; ++f)
    if (find(f) == f) column[f] = count++;
  std::vector<std::int32_t> outer(static_cast<std::size_t>(psi.rows()) + 1, 0), inner;
  std::vector<double> values;
  std::map<std::int32_t, double> row;
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    row.clear();
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) row[column[find(static_cast<std::size_t>(it.col()))]] += it.value();
    for (const auto& kv : row) inner.push_back(kv.first), values.push_back(kv.second);
    outer[static_cast<std::size_t>(i) + 1] = static_cast<std::int32_t>(values.size());
  }
  if (report) report->merges = merges, report->before = m, report->after = static_cast<std::size_t>(count);
  return from_rows(psi.rows(), count, outer, inner, values);
}

}  // namespace qf
