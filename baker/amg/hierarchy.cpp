// AMG coarsening (amg-notes.md section 4): sanitise -> strength -> Ruge-Stueben split -> direct
// interpolation (lumped) -> Galerkin product, level after level, with theta bisected for the ratio.
#include "amg/hierarchy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/hash.h"

namespace qf {
namespace {

enum : std::int8_t { kUndecided = 0, kCoarse = 1, kFine = 2 };

// Plain compressed rows of integers (the strength graph and its transpose).
struct Graph {
  std::vector<std::int32_t> ptr, idx;
  std::int32_t begin(std::size_t i) const { return ptr[i]; }
  std::int32_t end(std::size_t i) const { return ptr[i + 1]; }
};

// Step 1: exact symmetry, negligible entries dropped (symmetrically), zero row sums restored.
// Galerkin products carry rounding; this keeps every level's contract exact.
SparseMatrix sanitize(const SparseMatrix& a) { return symmetrize_zero_row_sums(a, 1e-12); }

// Step 2: j is a strong neighbour of i if a_ij < 0 and -a_ij >= theta max_k(-a_ik) (amg-notes 1.1).
Graph strength(const SparseMatrix& a, double theta) {
  const auto n = static_cast<std::size_t>(a.rows());
  Graph s;
  s.ptr.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    double strongest = 0;
    for (SparseMatrix::InnerIterator it(a, static_cast<Eigen::Index>(i)); it; ++it)
      if (it.col() != static_cast<Eigen::Index>(i)) strongest = std::max(strongest, -it.value());
    if (strongest > 0)
      for (SparseMatrix::InnerIterator it(a, static_cast<Eigen::Index>(i)); it; ++it)
        if (it.col() != static_cast<Eigen::Index>(i) && -it.value() >= theta * strongest && it.value() < 0)
          s.idx.push_back(static_cast<std::int32_t>(it.col()));
    s.ptr[i + 1] = static_cast<std::int32_t>(s.idx.size());
  }
  return s;
}

Graph transpose(const Graph& g, std::size_t n) {
  Graph t;
  t.ptr.assign(n + 1, 0);
  for (std::int32_t j : g.idx) ++t.ptr[static_cast<std::size_t>(j) + 1];
  for (std::size_t i = 0; i < n; ++i) t.ptr[i + 1] += t.ptr[i];
  t.idx.resize(g.idx.size());
  std::vector<std::int32_t> fill(t.ptr.begin(), t.ptr.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (std::int32_t r = g.begin(i); r < g.end(i); ++r) t.idx[static_cast<std::size_t>(fill[static_cast<std::size_t>(g.idx[static_cast<std::size_t>(r)])]++)] = static_cast<std::int32_t>(i);
  return t;
}

// The undecided points bucketed by lambda_i, each bucket a doubly linked list, so that the highest
// lambda is found in O(1) amortised as lambdas change.
struct LambdaBuckets {
  std::vector<std::int32_t> lambda, head, next, prev;
  std::int32_t top = 0;

  LambdaBuckets(const Graph& st, std::size_t n) : lambda(n), next(n, -1), prev(n, -1) {
    for (std::size_t i = 0; i < n; ++i) {
      lambda[i] = st.end(i) - st.begin(i);
      top = std::max(top, lambda[i]);
    }
    head.assign(static_cast<std::size_t>(2 * top + n + 2), -1);  // lambda can grow by F promotions
    for (std::size_t i = n; i-- > 0;) link(static_cast<std::int32_t>(i));  // lowest index on top of each bucket
  }
  void unlink(std::int32_t i) {
    const auto ui = static_cast<std::size_t>(i);
    if (prev[ui] >= 0) next[static_cast<std::size_t>(prev[ui])] = next[ui];
    else head[static_cast<std::size_t>(lambda[ui])] = next[ui];
    if (next[ui] >= 0) prev[static_cast<std::size_t>(next[ui])] = prev[ui];
    next[ui] = prev[ui] = -1;
  }
  void link(std::int32_t i) {
    const auto ui = static_cast<std::size_t>(i);
    const auto b = static_cast<std::size_t>(lambda[ui]);
    if (b >= head.size()) head.resize(b + 1, -1);
    next[ui] = head[b];
    prev[ui] = -1;
    if (head[b] >= 0) prev[static_cast<std::size_t>(head[b])] = i;
    head[b] = i;
    top = std::max(top, lambda[ui]);
  }
  // Moves i to the bucket of lambda_i + delta.
  void change(std::int32_t i, std::int32_t delta) {
    unlink(i);
    lambda[static_cast<std::size_t>(i)] += delta;
    link(i);
  }
  // Takes out the most recently bucketed point of the highest bucket above 0; -1 when none is left.
  std::int32_t pop_top() {
    while (top > 0 && head[static_cast<std::size_t>(top)] < 0) --top;
    if (top <= 0) return -1;
    const std::int32_t i = head[static_cast<std::size_t>(top)];
    unlink(i);
    return i;
  }
};

// Step 3a: Ruge-Stueben first pass with bucket lists on lambda_i = |S_i^T| (amg-notes 1.2). The
// next C point is the most recently bucketed point of the highest bucket: deterministic.
std::vector<std::int8_t> rs_first_pass(const Graph& s, const Graph& st, std::size_t n) {
  std::vector<std::int8_t> state(n, kUndecided);
  LambdaBuckets buckets(st, n);
  for (std::int32_t i; (i = buckets.pop_top()) >= 0;) {
    state[static_cast<std::size_t>(i)] = kCoarse;
    // Points that depend strongly on i become F; their other strong neighbours gain weight.
    for (std::int32_t r = st.begin(static_cast<std::size_t>(i)); r < st.end(static_cast<std::size_t>(i)); ++r) {
      const std::int32_t j = st.idx[static_cast<std::size_t>(r)];
      if (state[static_cast<std::size_t>(j)] != kUndecided) continue;
      buckets.unlink(j);
      state[static_cast<std::size_t>(j)] = kFine;
      for (std::int32_t q = s.begin(static_cast<std::size_t>(j)); q < s.end(static_cast<std::size_t>(j)); ++q) {
        const std::int32_t k = s.idx[static_cast<std::size_t>(q)];
        if (state[static_cast<std::size_t>(k)] == kUndecided) buckets.change(k, +1);
      }
    }
    // i's own strong neighbours lose one reason to become C.
    for (std::int32_t r = s.begin(static_cast<std::size_t>(i)); r < s.end(static_cast<std::size_t>(i)); ++r) {
      const std::int32_t j = s.idx[static_cast<std::size_t>(r)];
      if (state[static_cast<std::size_t>(j)] == kUndecided && buckets.lambda[static_cast<std::size_t>(j)] != 0) buckets.change(j, -1);
    }
  }
  // Left undecided (nobody depends on them): F if they have a strong C neighbour, else C.
  for (std::size_t i = 0; i < n; ++i) {
    if (state[i] != kUndecided) continue;
    bool has_c = false;
    for (std::int32_t r = s.begin(i); r < s.end(i) && !has_c; ++r) has_c = state[static_cast<std::size_t>(s.idx[static_cast<std::size_t>(r)])] == kCoarse;
    state[i] = has_c ? kFine : kCoarse;
  }
  return state;
}

// Step 3b: second pass. A strong F-F pair without a common strong C point cannot share its
// coupling through interpolation; make the neighbour C (amg-notes 1.2; this brings the ratio
// from ~4 to ~2.5 on surface meshes).
void rs_second_pass(const Graph& s, std::size_t n, std::vector<std::int8_t>& state) {
  std::vector<std::int32_t> mark(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (state[i] != kFine) continue;
    for (std::int32_t r = s.begin(i); r < s.end(i); ++r) {
      const auto k = static_cast<std::size_t>(s.idx[static_cast<std::size_t>(r)]);
      if (state[k] == kCoarse) mark[k] = static_cast<std::int32_t>(i);
    }
    for (std::int32_t r = s.begin(i); r < s.end(i); ++r) {
      const auto j = static_cast<std::size_t>(s.idx[static_cast<std::size_t>(r)]);
      if (state[j] != kFine) continue;
      bool shared = false;
      for (std::int32_t q = s.begin(j); q < s.end(j) && !shared; ++q) shared = mark[static_cast<std::size_t>(s.idx[static_cast<std::size_t>(q)])] == static_cast<std::int32_t>(i);
      if (!shared) {
        state[j] = kCoarse;
        mark[j] = static_cast<std::int32_t>(i);
      }
    }
  }
}

// Step 5: direct interpolation with positive and weak couplings lumped: for an F point,
// w_ij = a_ij / sum_{k in C_i} a_ik over its strong negative C neighbours (or, failing those, all
// its negative C neighbours). An F point with no negative C neighbour at all becomes C first.
// Rows are non-negative and sum to 1 by construction; columns are numbered in fine index order.
SparseMatrix interpolation(const SparseMatrix& a, const Graph& s, std::vector<std::int8_t>& state) {
  const auto n = static_cast<std::size_t>(a.rows());
  std::vector<std::int32_t> mark(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (state[i] != kFine) continue;
    bool any = false;
    for (SparseMatrix::InnerIterator it(a, static_cast<Eigen::Index>(i)); it && !any; ++it)
      any = it.col() != static_cast<Eigen::Index>(i) && it.value() < 0 && state[static_cast<std::size_t>(it.col())] == kCoarse;
    if (!any) state[i] = kCoarse;
  }
  std::vector<std::int32_t> coarse(n, -1);
  std::int32_t nc = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (state[i] == kCoarse) coarse[i] = nc++;
  std::vector<std::int32_t> outer(n + 1, 0), inner;
  std::vector<double> values;
  std::vector<std::pair<std::int32_t, double>> row;
  for (std::size_t i = 0; i < n; ++i) {
    row.clear();
    if (state[i] == kCoarse) {
      row.push_back({coarse[i], 1.0});
    } else {
      for (std::int32_t r = s.begin(i); r < s.end(i); ++r) mark[static_cast<std::size_t>(s.idx[static_cast<std::size_t>(r)])] = static_cast<std::int32_t>(i);
      for (int pass = 0; pass < 2 && row.empty(); ++pass) {
        double sum = 0;
        for (SparseMatrix::InnerIterator it(a, static_cast<Eigen::Index>(i)); it; ++it) {
          const auto j = static_cast<std::size_t>(it.col());
          if (j == i || it.value() >= 0 || state[j] != kCoarse) continue;
          if (pass == 0 && mark[j] != static_cast<std::int32_t>(i)) continue;  // first try strong ones only
          row.push_back({coarse[j], it.value()});
          sum += it.value();
        }
        for (auto& e : row) e.second /= sum;
      }
      std::sort(row.begin(), row.end());
    }
    for (const auto& e : row) inner.push_back(e.first), values.push_back(e.second);
    outer[i + 1] = static_cast<std::int32_t>(values.size());
  }
  SparseMatrix p(static_cast<Eigen::Index>(n), nc);
  p.resizeNonZeros(static_cast<Eigen::Index>(values.size()));
  std::copy(outer.begin(), outer.end(), p.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), p.innerIndexPtr());
  std::copy(values.begin(), values.end(), p.valuePtr());
  return p;
}

// Steps 2-5 with theta bisected until the ratio lands in the target range (amg-notes 4.4), or,
// with `aim` > 0, until the coarse size is nearest `aim` (AmgOptions::target_sizes; within 0.5%
// ends the search).
SparseMatrix coarsen(const SparseMatrix& a, const AmgOptions& o, double& theta_used, std::size_t aim) {
  const auto n = static_cast<std::size_t>(a.rows());
  double lo = 0.01, hi = 0.99, theta = theta_used;
  SparseMatrix best;
  double best_miss = INFINITY;
  const int tries = aim ? std::max(o.ratio_tries, kAimTries) : std::max(1, o.ratio_tries);
  for (int t = 0; t < tries; ++t) {
    const Graph s = strength(a, theta);
    const Graph st = transpose(s, n);
    std::vector<std::int8_t> state = rs_first_pass(s, st, n);
    rs_second_pass(s, n, state);
    SparseMatrix p = interpolation(a, s, state);
    const double ratio = p.cols() ? double(n) / double(p.cols()) : INFINITY;
    const double miss = aim ? std::fabs(double(p.cols()) - double(aim)) / double(aim)
                        : ratio < o.target_ratio_min ? o.target_ratio_min - ratio
                        : ratio > o.target_ratio_max ? ratio - o.target_ratio_max : 0.0;
    const bool too_coarse = aim ? std::size_t(p.cols()) < aim : ratio > o.target_ratio_max;
    if (miss < best_miss) best_miss = miss, best = std::move(p), theta_used = theta;
    if (aim ? miss <= 0.005 : miss == 0) break;
    // A higher theta keeps fewer strong couplings, so more points become C: the ratio falls.
    if (too_coarse) lo = theta;
    else hi = theta;
    theta = 0.5 * (lo + hi);
  }
  return best;
}

// The size the next level aims at from a level of `fine` functions (0 = none, the ratio rule):
// for the largest target T of o.target_sizes with fine / T = r in [1.5, 27], the level k steps
// before T, each of ratio r^(1/k): one step up to r = 4.5, else as many as ratios of at most 3
// need (ruge-stueben splits of ratio under ~2 are rare: a level of 156 aimed at 100 gave 77).
std::size_t aimed_size(const AmgOptions& o, std::size_t fine) {
  std::size_t target = 0;
  for (std::size_t t : o.target_sizes) {
    const double r = t > 0 ? double(fine) / double(t) : 0.0;
    if (r >= 1.5 && r <= 27.0) target = std::max(target, t);
  }
  if (!target) return 0;
  const double r = double(fine) / double(target);
  const double steps = r <= 4.5 ? 1.0 : std::ceil(std::log(r) / std::log(3.0));
  return static_cast<std::size_t>(std::llround(double(fine) / std::pow(r, 1.0 / steps)));
}

// Breadth-first order of the matrix graph, component by component from the lowest index;
// neighbours in column order. Deterministic. Also counts the connected parts and the rows
// without any off-diagonal coupling.
std::vector<std::uint32_t> breadth_first_order(const SparseMatrix& a, std::size_t& components, std::size_t& isolated) {
  const auto n = static_cast<std::size_t>(a.rows());
  std::vector<std::uint32_t> order;
  order.reserve(n);
  std::vector<char> seen(n, 0);
  components = isolated = 0;
  for (std::size_t i = 0; i < n; ++i) {
    bool coupled = false;
    for (SparseMatrix::InnerIterator it(a, static_cast<Eigen::Index>(i)); it && !coupled; ++it)
      coupled = it.col() != static_cast<Eigen::Index>(i) && it.value() != 0;
    isolated += !coupled;
  }
  for (std::size_t start = 0; start < n; ++start) {
    if (seen[start]) continue;
    ++components;
    seen[start] = 1;
    order.push_back(static_cast<std::uint32_t>(start));
    for (std::size_t q = order.size() - 1; q < order.size(); ++q)
      for (SparseMatrix::InnerIterator it(a, static_cast<Eigen::Index>(order[q])); it; ++it)
        if (!seen[static_cast<std::size_t>(it.col())]) {
          seen[static_cast<std::size_t>(it.col())] = 1;
          order.push_back(static_cast<std::uint32_t>(it.col()));
        }
  }
  return order;
}

// Q A Q^T: row r of the result is row order[r] of A, columns renumbered and sorted. Written
// straight into the matrix (no intermediate arrays: at 10M points they were ~1 GB).
SparseMatrix permute_symmetric(const SparseMatrix& a, const std::vector<std::uint32_t>& order) {
  const std::size_t n = order.size();
  std::vector<std::int32_t> inverse(n);
  for (std::size_t r = 0; r < n; ++r) inverse[order[r]] = static_cast<std::int32_t>(r);
  SparseMatrix out(a.rows(), a.cols());
  out.resizeNonZeros(a.nonZeros());
  std::int32_t* outer = out.outerIndexPtr();
  outer[0] = 0;
  std::vector<std::pair<std::int32_t, double>> row;
  for (std::size_t r = 0; r < n; ++r) {
    row.clear();
    for (SparseMatrix::InnerIterator it(a, static_cast<Eigen::Index>(order[r])); it; ++it)
      row.push_back({inverse[static_cast<std::size_t>(it.col())], it.value()});
    std::sort(row.begin(), row.end());
    for (std::size_t e = 0; e < row.size(); ++e) {
      out.innerIndexPtr()[outer[r] + static_cast<std::int32_t>(e)] = row[e].first;
      out.valuePtr()[outer[r] + static_cast<std::int32_t>(e)] = row[e].second;
    }
    outer[r + 1] = outer[r] + static_cast<std::int32_t>(row.size());
  }
  return out;
}

// build_hierarchy's levels from A, renumbered into breadth-first order; `a0` is freed once
// renumbered when the caller gives it up (`release`), so two copies of the finest matrix never
// live through the coarsening.
AmgHierarchy build_levels(const SparseMatrix& a0, SparseMatrix* release, const AmgOptions& options) {
  AmgHierarchy h;
  const auto n = static_cast<std::size_t>(a0.rows());
  h.levels.push_back({n, 0.0, 1.0});
  // The input is symmetric with zero row sums by contract (stiffness.h); it is only renumbered.
  h.fine_order = breadth_first_order(a0, h.components, h.isolated);
  SparseMatrix a = permute_symmetric(a0, h.fine_order);
  if (release) *release = SparseMatrix();
  double theta = options.theta;
  while (static_cast<int>(h.levels.size()) < options.max_levels && h.levels.back().size > options.stop_size) {
    // Start from the threshold that suited the level above: neighbouring levels behave alike.
    const auto t0 = std::chrono::steady_clock::now();
    const double theta_before = theta;
    const std::size_t aim = aimed_size(options, h.levels.back().size);
    SparseMatrix p = coarsen(a, options, theta, aim);
    if (aim) theta = theta_before;  // an aimed level's threshold is no guide to the next
    const auto t1 = std::chrono::steady_clock::now();
    const std::size_t fine = static_cast<std::size_t>(a.rows()), coarse = static_cast<std::size_t>(p.cols());
    const double ratio = coarse ? double(fine) / double(coarse) : 0.0;
    if (coarse == 0 || ratio < 1.1) break;  // stalled: only uncoupled parts are left
    // Galerkin: A_c = P^T A P, then exact symmetry and zero row sums again.
    a = sanitize(galerkin_product(a, p));
    const auto t2 = std::chrono::steady_clock::now();
    h.P.push_back(std::move(p));
    h.levels.push_back({coarse, theta, ratio, std::chrono::duration<double>(t1 - t0).count(),
                        std::chrono::duration<double>(t2 - t1).count()});
  }
  return h;
}

}  // namespace

AmgHierarchy build_hierarchy(const SparseMatrix& a, const AmgOptions& options) { return build_levels(a, nullptr, options); }

AmgHierarchy build_hierarchy(SparseMatrix&& a, const AmgOptions& options) { return build_levels(a, &a, options); }

std::size_t level_by_index(const AmgHierarchy& h, long long k) {
  const auto count = static_cast<long long>(h.level_count());
  const long long level = k >= 0 ? k : count - 1 + k;
  if (level < 0 || level >= count)
    throw std::out_of_range("level " + std::to_string(k) + " does not exist: the hierarchy has levels 0.." +
                            std::to_string(count - 1) + " (or -" + std::to_string(count - 1) + "..0 from the coarsest)");
  return static_cast<std::size_t>(level);
}

std::size_t level_by_primitives(const AmgHierarchy& h, std::size_t primitives) {
  std::size_t best = 0;
  for (std::size_t l = 0; l < h.level_count(); ++l) {
    const auto miss = [&](std::size_t x) { return x > primitives ? x - primitives : primitives - x; };
    if (miss(h.levels[l].size) <= miss(h.levels[best].size)) best = l;  // later = coarser wins ties
  }
  return best;
}

std::uint64_t hierarchy_hash(const AmgHierarchy& h) {
  Sha256 x;
  auto feed = [&](const void* data, std::size_t bytes) { x.update(ByteView(static_cast<const std::uint8_t*>(data), bytes)); };
  for (const AmgLevel& l : h.levels) feed(&l.size, sizeof l.size);
  feed(h.fine_order.data(), sizeof(std::uint32_t) * h.fine_order.size());
  for (const SparseMatrix& p : h.P) {
    feed(p.outerIndexPtr(), sizeof(std::int32_t) * static_cast<std::size_t>(p.outerSize() + 1));
    feed(p.innerIndexPtr(), sizeof(std::int32_t) * static_cast<std::size_t>(p.nonZeros()));
    feed(p.valuePtr(), sizeof(double) * static_cast<std::size_t>(p.nonZeros()));
  }
  return x.digest64();
}

}  // namespace qf
