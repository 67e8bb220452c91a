// Greedy domain merging with additive Psi-weighted moments (thesis 3.4), then sliver absorption and
// crease trimming (issue 15 item 4: one quad per face of the octahedron and the cube).
#include "domains/merge.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
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

// Step 1, part 1: per-function moments, relative to the bounding-box centre (returned in `origin`).
std::vector<Moments> function_moments(const SparseMatrix& psi, const std::vector<Vec3f>& positions, Eigen::Vector3d& origin) {
  Bounds box;
  for (const Vec3f& p : positions) box.add(p);
  const Vec3f c = box.center();
  origin = Eigen::Vector3d(c.x, c.y, c.z);
  std::vector<Moments> moments(static_cast<std::size_t>(psi.cols()));
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
  return moments;
}

// Step 1, part 2: pairwise overlaps of the thresholded domains. overlap[f][g]: shared points (both
// directions), counted from each point's memberships.
std::vector<std::map<std::size_t, double>> domain_overlaps(const SparseMatrix& psi, const DomainOptions& options) {
  const Domains d = make_domains(psi, options);
  std::vector<std::map<std::size_t, double>> overlap(static_cast<std::size_t>(psi.cols()));
  std::vector<std::vector<std::uint32_t>> of_point(static_cast<std::size_t>(psi.rows()));
  for (std::size_t f = 0; f < d.count(); ++f)
    for (std::uint32_t r = d.offsets[f]; r < d.offsets[f + 1]; ++r) of_point[d.points[r]].push_back(static_cast<std::uint32_t>(f));
  for (const auto& list : of_point)
    for (std::size_t a = 0; a < list.size(); ++a)
      for (std::size_t b = a + 1; b < list.size(); ++b) overlap[list[a]][list[b]] += 1, overlap[list[b]][list[a]] += 1;
  return overlap;
}

// The merged groups of basis functions: union-find with path halving, the lowest index of a group
// its representative.
struct Groups {
  std::vector<std::size_t> parent;
  explicit Groups(std::size_t m) : parent(m) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
};

// A pair of groups that may merge, and how many points their domains share.
struct Candidate {
  double shared;
  std::size_t a, b;
  bool operator<(const Candidate& o) const {  // max-heap on shared, then lowest (a, b)
    if (shared != o.shared) return shared < o.shared;
    return std::tie(a, b) > std::tie(o.a, o.b);
  }
};

// Step 1, part 3: greedy, the qualifying pair with the largest overlap first (ties: lowest
// indices). Both planes flat and within max_angle of each other; returns the number of merges.
std::size_t merge_pairs(std::vector<std::map<std::size_t, double>>& overlap, std::vector<Moments>& moments,
                        const Eigen::Vector3d& origin, const MergeOptions& options, Groups& groups) {
  std::priority_queue<Candidate> heap;
  for (std::size_t f = 0; f < overlap.size(); ++f)
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
    const std::size_t a = groups.find(cand.a), b = groups.find(cand.b);
    if (a == b) continue;
    const auto current = overlap[a].find(b);
    if (a != cand.a || b != cand.b || current == overlap[a].end() || current->second != cand.shared) continue;  // stale
    if (!qualifies(a, b)) continue;
    // Merge b into a (the lower index stays the representative).
    const std::size_t keep = std::min(a, b), gone = std::max(a, b);
    groups.parent[gone] = keep;
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
  return merges;
}

// Step 1, part 4: Psi' = Psi M with groups numbered in order of their representatives.
SparseMatrix merged_basis(const SparseMatrix& psi, Groups& groups) {
  const auto m = static_cast<std::size_t>(psi.cols());
  std::vector<std::int32_t> column(m, -1);
  std::int32_t count = 0;
  for (std::size_t f = 0; f < m; ++f)
    if (groups.find(f) == f) column[f] = count++;
  std::vector<std::int32_t> outer(static_cast<std::size_t>(psi.rows()) + 1, 0), inner;
  std::vector<double> values;
  std::map<std::int32_t, double> row;
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    row.clear();
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) row[column[groups.find(static_cast<std::size_t>(it.col()))]] += it.value();
    for (const auto& kv : row) inner.push_back(kv.first), values.push_back(kv.second);
    outer[static_cast<std::size_t>(i) + 1] = static_cast<std::int32_t>(values.size());
  }
  return from_rows(psi.rows(), count, outer, inner, values);
}

// Step 1: the thesis' greedy merge of flat domains that overlap and face the same way; Psi M with
// groups numbered in order of their representatives. merges_out: the number of merges.
SparseMatrix greedy_merge(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const MergeOptions& options,
                          std::size_t& merges_out) {
  Eigen::Vector3d origin;
  std::vector<Moments> moments = function_moments(psi, positions, origin);
  std::vector<std::map<std::size_t, double>> overlap = domain_overlaps(psi, options.domains);
  Groups groups(static_cast<std::size_t>(psi.cols()));
  merges_out = merge_pairs(overlap, moments, origin, options, groups);
  return merged_basis(psi, groups);
}

// What the cleaning steps need of a domain: its Psi mass, weighted plane (normal oriented by the
// weighted mean point normal) and how well its points' normals agree (|weighted mean normal|).
struct Shape {
  double mass = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::UnitZ();
  double coherence = 1;  // 1 without normals
};

Eigen::Vector3d v3(Vec3f p) { return {double(p.x), double(p.y), double(p.z)}; }

std::vector<Shape> shapes_of(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals) {
  const auto m = static_cast<std::size_t>(psi.cols());
  Bounds box;
  for (const Vec3f& p : positions) box.add(p);
  const Eigen::Vector3d origin = v3(box.center());
  std::vector<Moments> mo(m);
  std::vector<Eigen::Vector3d> nsum(m, Eigen::Vector3d::Zero());
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    const Eigen::Vector3d x = v3(positions[static_cast<std::size_t>(i)]) - origin;
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) {
      const auto c = static_cast<std::size_t>(it.col());
      mo[c].w += it.value(), mo[c].s += it.value() * x, mo[c].ss += it.value() * x * x.transpose();
      if (!normals.empty()) nsum[c] += it.value() * v3(normals[static_cast<std::size_t>(i)]);
    }
  }
  std::vector<Shape> out(m);
  for (std::size_t c = 0; c < m; ++c) {
    if (!(mo[c].w > 0)) continue;
    Shape& s = out[c];
    s.mass = mo[c].w;
    s.centroid = mo[c].s / mo[c].w + origin;
    s.normal = plane_of(mo[c], origin).normal;
    if (!normals.empty()) {
      s.coherence = nsum[c].norm() / mo[c].w;
      if (s.normal.dot(nsum[c]) < 0) s.normal = -s.normal;
    }
  }
  return out;
}

// Step 2, part 1: the heaviest neighbour of each domain (its mass): per row, the two heaviest
// domains in it.
std::vector<double> heaviest_neighbors(const SparseMatrix& psi, const std::vector<Shape>& shapes) {
  std::vector<double> heaviest(static_cast<std::size_t>(psi.cols()), 0.0);
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    std::int64_t first = -1, second = -1;
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) {
      const std::int64_t c = it.col();
      if (first < 0 || shapes[std::size_t(c)].mass > shapes[std::size_t(first)].mass) second = first, first = c;
      else if (second < 0 || shapes[std::size_t(c)].mass > shapes[std::size_t(second)].mass) second = c;
    }
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) {
      const std::int64_t other = it.col() == first ? second : first;
      if (other >= 0) heaviest[std::size_t(it.col())] = std::max(heaviest[std::size_t(it.col())], shapes[std::size_t(other)].mass);
    }
  }
  return heaviest;
}

// Step 2, part 2: slivers, light next to a neighbour, or lighter but with their normals split.
std::vector<char> find_slivers(const std::vector<Shape>& shapes, const std::vector<double>& heaviest, bool has_normals,
                               const MergeOptions& o) {
  const double cos_split = std::cos(o.straddle_angle_degrees * 3.14159265358979323846 / 180.0);
  std::vector<char> sliver(shapes.size(), 0);
  for (std::size_t c = 0; c < shapes.size(); ++c)
    sliver[c] = shapes[c].mass < o.sliver_share * heaviest[c] ||
                (has_normals && shapes[c].mass < o.straddle_share * heaviest[c] && shapes[c].coherence < cos_split);
  return sliver;
}

// Step 2, part 3: each sliver's non-sliver neighbours (sorted, unique); `slivers` counts the
// slivers that have one.
std::vector<std::vector<std::uint32_t>> sliver_targets(const SparseMatrix& psi, const std::vector<char>& sliver, std::size_t& slivers) {
  std::vector<std::vector<std::uint32_t>> targets(static_cast<std::size_t>(psi.cols()));
  for (Eigen::Index i = 0; i < psi.rows(); ++i)
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it)
      if (sliver[std::size_t(it.col())])
        for (SparseMatrix::InnerIterator jt(psi, i); jt; ++jt)
          if (!sliver[std::size_t(jt.col())]) targets[std::size_t(it.col())].push_back(static_cast<std::uint32_t>(jt.col()));
  slivers = 0;
  for (auto& t : targets) {
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
    slivers += !t.empty();
  }
  return targets;
}

// Step 2, part 4: move the weights, point by point, from each sliver with targets to the
// candidate that fits the point best.
SparseMatrix move_sliver_weights(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                 const std::vector<Shape>& shapes, const std::vector<char>& sliver,
                                 const std::vector<std::vector<std::uint32_t>>& targets) {
  Bounds box;
  for (const Vec3f& p : positions) box.add(p);
  const double diag = std::max(double(box.diagonal()), 1e-30);
  std::vector<std::int32_t> outer(static_cast<std::size_t>(psi.rows()) + 1, 0), inner;
  std::vector<double> values;
  std::map<std::int32_t, double> row;
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    row.clear();
    const Eigen::Vector3d x = v3(positions[static_cast<std::size_t>(i)]);
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) {
      const auto c = static_cast<std::size_t>(it.col());
      if (targets[c].empty()) {
        row[static_cast<std::int32_t>(c)] += it.value();
        continue;
      }
      // The best fitting candidate: lowest (1 - n.N) + distance / diagonal, lowest index on ties.
      double best_cost = INFINITY;
      std::int32_t best = -1;
      auto consider = [&](std::size_t g) {
        if (sliver[g]) return;
        double cost = std::fabs(shapes[g].normal.dot(x - shapes[g].centroid)) / diag;
        if (!normals.empty()) cost += 1.0 - shapes[g].normal.dot(v3(normals[static_cast<std::size_t>(i)]));
        if (cost < best_cost || (cost == best_cost && std::int32_t(g) < best)) best_cost = cost, best = std::int32_t(g);
      };
      for (std::uint32_t g : targets[c]) consider(g);
      for (SparseMatrix::InnerIterator jt(psi, i); jt; ++jt) consider(static_cast<std::size_t>(jt.col()));
      row[best] += it.value();
    }
    for (const auto& kv : row) inner.push_back(kv.first), values.push_back(kv.second);
    outer[static_cast<std::size_t>(i) + 1] = static_cast<std::int32_t>(values.size());
  }
  return from_rows(psi.rows(), psi.cols(), outer, inner, values);
}

// Step 2: slivers. A domain's neighbours here are the domains it shares a point with (any weight,
// so a sliver whose weights never exceed tau is found too). Each point's weight in a sliver goes
// to the non-sliver domain that fits the point best (normal first, distance to its plane second),
// among the point's own domains and the sliver's neighbours. A sliver without a non-sliver
// neighbour stays. `slivers`: the number absorbed.
SparseMatrix absorb_slivers(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                            const std::vector<Shape>& shapes, const MergeOptions& o, std::size_t& slivers) {
  const std::vector<char> sliver = find_slivers(shapes, heaviest_neighbors(psi, shapes), !normals.empty(), o);
  const std::vector<std::vector<std::uint32_t>> targets = sliver_targets(psi, sliver, slivers);
  if (slivers == 0) return psi;
  return move_sliver_weights(psi, positions, normals, shapes, sliver, targets);
}

// Step 3: creases. A point whose normal lies within crease_angle of some of its domains' planes
// gives its weight in the others (beyond crease_angle) to those, in proportion to their weights.
SparseMatrix trim_creases(const SparseMatrix& psi, const std::vector<Vec3f>& normals, const std::vector<Shape>& shapes,
                          const std::vector<std::array<std::uint32_t, 2>>& edges, const MergeOptions& o, std::size_t& trimmed) {
  std::vector<std::vector<std::uint32_t>> nb(static_cast<std::size_t>(psi.cols()));
  for (const auto& e : edges) nb[e[0]].push_back(e[1]), nb[e[1]].push_back(e[0]);
  const double cos_crease = std::cos(o.crease_angle_degrees * 3.14159265358979323846 / 180.0);
  std::vector<std::int32_t> outer(static_cast<std::size_t>(psi.rows()) + 1, 0), inner;
  std::vector<double> values;
  trimmed = 0;
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    const Eigen::Vector3d n = v3(normals[static_cast<std::size_t>(i)]);
    auto fitting = [&](std::size_t c) { return shapes[c].normal.dot(n) >= cos_crease; };
    double kept = 0, moved = 0;
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it)
      (fitting(static_cast<std::size_t>(it.col())) ? kept : moved) += it.value();
    if (kept == 0 && moved > 0) {
      // None of the point's domains faces its way (a corner where the face's own domain does
      // not reach): all its weight goes to the best-facing neighbour of its domains, if one fits.
      double best_fit = cos_crease;
      std::int32_t best = -1;
      for (SparseMatrix::InnerIterator it(psi, i); it; ++it)
        for (std::uint32_t g : nb[static_cast<std::size_t>(it.col())]) {
          const double fit = shapes[g].normal.dot(n);
          if (fit > best_fit || (fit == best_fit && best >= 0 && std::int32_t(g) < best)) best_fit = fit, best = std::int32_t(g);
        }
      if (best >= 0) {
        for (SparseMatrix::InnerIterator it(psi, i); it; ++it) ++trimmed;
        inner.push_back(best);
        values.push_back(moved);
        outer[static_cast<std::size_t>(i) + 1] = static_cast<std::int32_t>(values.size());
        continue;
      }
    }
    const bool trim = kept > 0 && moved > 0;
    for (SparseMatrix::InnerIterator it(psi, i); it; ++it) {
      const bool fits = fitting(static_cast<std::size_t>(it.col()));
      if (trim && !fits) {
        ++trimmed;
        continue;
      }
      inner.push_back(static_cast<std::int32_t>(it.col()));
      values.push_back(trim ? it.value() * (kept + moved) / kept : it.value());
    }
    outer[static_cast<std::size_t>(i) + 1] = static_cast<std::int32_t>(values.size());
  }
  return from_rows(psi.rows(), psi.cols(), outer, inner, values);
}

// Step 4: columns without any weight left are removed, the others keep their order; `column`
// receives each old column's new index (-1: removed).
SparseMatrix drop_empty_columns(const SparseMatrix& psi, std::vector<std::int32_t>& column) {
  column.assign(static_cast<std::size_t>(psi.cols()), -1);
  for (Eigen::Index k = 0; k < psi.nonZeros(); ++k) column[static_cast<std::size_t>(psi.innerIndexPtr()[k])] = 0;
  std::int32_t count = 0;
  for (std::int32_t& c : column)
    if (c == 0) c = count++;
  if (count == psi.cols()) return psi;
  std::vector<std::int32_t> outer(psi.outerIndexPtr(), psi.outerIndexPtr() + psi.rows() + 1), inner;
  inner.reserve(static_cast<std::size_t>(psi.nonZeros()));
  for (Eigen::Index k = 0; k < psi.nonZeros(); ++k) inner.push_back(column[static_cast<std::size_t>(psi.innerIndexPtr()[k])]);
  return from_rows(psi.rows(), count, outer, inner, std::vector<double>(psi.valuePtr(), psi.valuePtr() + psi.nonZeros()));
}

}  // namespace

SparseMatrix merge_domains(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                           const MergeOptions& options, MergeReport* report) {
  MergeReport r;
  r.before = static_cast<std::size_t>(psi.cols());
  SparseMatrix out = greedy_merge(psi, positions, options, r.merges);
  if (options.crease_true) {
    out = absorb_slivers(out, positions, normals, shapes_of(out, positions, normals), options, r.slivers);
    // The neighbour graph as the domains touch before trimming: faces meeting at a crease stay
    // neighbours (the overlap renderer blends a quad's neighbours before locking it).
    DomainOptions touch = options.domains;
    touch.neighbor_share = options.crease_neighbor_share;
    const std::vector<std::array<std::uint32_t, 2>> touching = make_domains(out, touch).edges;
    if (!normals.empty()) out = trim_creases(out, normals, shapes_of(out, positions, normals), touching, options, r.trimmed);
    std::vector<std::int32_t> column;
    out = drop_empty_columns(out, column);
    for (const auto& e : touching)
      if (column[e[0]] >= 0 && column[e[1]] >= 0)
        r.edges.push_back({static_cast<std::uint32_t>(column[e[0]]), static_cast<std::uint32_t>(column[e[1]])});
  } else {
    r.edges = make_domains(out, options.domains).edges;
  }
  r.after = static_cast<std::size_t>(out.cols());
  if (report) *report = std::move(r);
  return out;
}

SparseMatrix merge_domains(const SparseMatrix& psi, const std::vector<Vec3f>& positions, const MergeOptions& options,
                           MergeReport* report) {
  MergeOptions plain = options;
  plain.crease_true = false;
  return merge_domains(psi, positions, {}, plain, report);
}

std::size_t count_domains(const SparseMatrix& psi, const DomainOptions& options) {
  const Domains d = make_domains(psi, options);
  return d.count() - d.empty;
}

}  // namespace qf
