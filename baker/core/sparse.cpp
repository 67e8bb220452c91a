// Shared sparse-matrix operations: symmetrisation with zero row sums, Galerkin product.
#include "core/sparse.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cmath>

namespace qf {

namespace {

// Builds an n_rows x n_cols matrix row by row over every core. Rows go in chunks of kRowChunk,
// handed out dynamically (a thread that the machine's other jobs slow down, or that drew costly
// rows, does not hold the others up at the end); each thread owns a Scratch (made by
// make_scratch) and one pair of buffers it appends its chunks to; row(i, scratch, cols, vals)
// appends row i's entries in increasing column order. Chunks are joined in row order, so the
// result does not depend on the thread count or schedule. One buffer per thread, not per chunk:
// thousands of chunk buffers fragmented the heap (10M points: +1.3 GB peak in the basis stage).
// `expected` is the expected number of entries in all, to reserve the buffers once (growing them
// copies into fresh pages, which is slow on the project's machines).
constexpr std::size_t kRowChunk = 2048;

template <class MakeScratch, class Row>
SparseMatrix rows_in_parallel(std::size_t n_rows, Eigen::Index n_cols, std::size_t expected, MakeScratch&& make_scratch,
                              Row&& row) {
  std::vector<std::int32_t> outer(n_rows + 1, 0);
  const std::size_t chunks = (n_rows + kRowChunk - 1) / kRowChunk;
  struct Placed {
    std::size_t thread = 0, begin = 0;  // where a chunk's entries went
  };
  std::vector<Placed> placed(chunks);
  std::vector<std::vector<std::int32_t>> block_cols;
  std::vector<std::vector<double>> block_vals;
#pragma omp parallel
  {
#pragma omp single
    {
      block_cols.resize(static_cast<std::size_t>(omp_get_num_threads()));
      block_vals.resize(block_cols.size());
    }
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    auto scratch = make_scratch();
    auto& cols = block_cols[t];
    auto& vals = block_vals[t];
    cols.reserve(expected / block_cols.size() + 1024);
    vals.reserve(expected / block_cols.size() + 1024);
#pragma omp for schedule(dynamic)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(chunks); ++c) {
      placed[static_cast<std::size_t>(c)] = {t, cols.size()};
      const std::size_t first = static_cast<std::size_t>(c) * kRowChunk, last = std::min(n_rows, first + kRowChunk);
      for (std::size_t i = first; i < last; ++i) {
        const std::size_t before = cols.size();
        row(i, scratch, cols, vals);
        outer[i + 1] = static_cast<std::int32_t>(cols.size() - before);
      }
    }
  }
  for (std::size_t i = 0; i < n_rows; ++i) outer[i + 1] += outer[i];
  // Straight into the matrix: two copies of the entries at most (three through intermediate
  // arrays and from_rows: ~24 bytes per entry more at the peak).
  SparseMatrix m(static_cast<Eigen::Index>(n_rows), n_cols);
  m.resizeNonZeros(static_cast<Eigen::Index>(outer[n_rows]));
  std::copy(outer.begin(), outer.end(), m.outerIndexPtr());
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t first = c * kRowChunk, last = std::min(n_rows, first + kRowChunk);
    const auto count = static_cast<std::size_t>(outer[last] - outer[first]);
    const Placed& p = placed[c];
    std::copy_n(block_cols[p.thread].begin() + static_cast<std::ptrdiff_t>(p.begin), count, m.innerIndexPtr() + outer[first]);
    std::copy_n(block_vals[p.thread].begin() + static_cast<std::ptrdiff_t>(p.begin), count, m.valuePtr() + outer[first]);
  }
  return m;
}

// A dense accumulator for one sparse row: values by column, and the columns touched.
struct RowAccumulator {
  explicit RowAccumulator(std::size_t n) : value(n, 0.0), seen(n, 0) {}
  void add(std::int32_t j, double v) {
    const auto u = static_cast<std::size_t>(j);
    if (!seen[u]) seen[u] = 1, touched.push_back(j);
    value[u] += v;
  }
  std::vector<double> value;
  std::vector<char> seen;
  std::vector<std::int32_t> touched;
};

}  // namespace

SparseMatrix from_rows(Eigen::Index rows, Eigen::Index cols, const std::vector<std::int32_t>& outer,
                       const std::vector<std::int32_t>& inner, const std::vector<double>& values) {
  SparseMatrix m(rows, cols);
  m.resizeNonZeros(static_cast<Eigen::Index>(values.size()));
  std::copy(outer.begin(), outer.end(), m.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), m.innerIndexPtr());
  std::copy(values.begin(), values.end(), m.valuePtr());
  return m;
}

SparseMatrix symmetrize_zero_row_sums(const SparseMatrix& a, double drop, SymmetrizeReport* report) {
  const SparseMatrix t = a.transpose();
  const auto n = static_cast<std::size_t>(a.rows());
  std::vector<double> diag(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) diag[i] = std::fabs(a.coeff(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)));
  std::atomic<std::size_t> one_sided{0}, empty_rows{0};
  SparseMatrix s = rows_in_parallel(
      n, a.cols(), static_cast<std::size_t>(a.nonZeros()) + n, [] { return 0; },
      [&](std::size_t i, int&, std::vector<std::int32_t>& cols, std::vector<double>& vals) {
        const auto row = static_cast<Eigen::Index>(i);
        SparseMatrix::InnerIterator p(a, row), q(t, row);
        std::size_t diagonal = SIZE_MAX, entries = 0, one_side = 0;
        double sum = 0;
        auto put_diagonal_before = [&](Eigen::Index col) {
          if (diagonal == SIZE_MAX && col > row) {
            diagonal = vals.size();
            cols.push_back(static_cast<std::int32_t>(i));
            vals.push_back(0.0);  // set below
          }
        };
        // Merge row i of A and of A^T (both sorted by column).
        while (p || q) {
          const Eigen::Index cp = p ? p.col() : a.cols(), cq = q ? q.col() : a.cols();
          const Eigen::Index col = std::min(cp, cq);
          const double x = cp == col ? p.value() : 0.0, y = cq == col ? q.value() : 0.0;
          if (cp == col) ++p;
          if (cq == col) ++q;
          if (col == row) continue;
          one_side += (cp != cq);
          const double v = 0.5 * (x + y);
          if (v == 0.0 || std::fabs(v) <= drop * std::max(diag[i], diag[static_cast<std::size_t>(col)])) continue;
          put_diagonal_before(col);
          cols.push_back(static_cast<std::int32_t>(col));
          vals.push_back(v);
          sum += v;
          ++entries;
        }
        put_diagonal_before(a.cols());
        vals[diagonal] = -sum;
        if (one_side) one_sided += one_side;
        if (entries == 0) ++empty_rows;
      });
  if (report) report->one_sided = one_sided / 2, report->empty_rows = empty_rows;
  return s;
}

SparseMatrix galerkin_product(const SparseMatrix& a, const SparseMatrix& p) {
  const SparseMatrix pt = p.transpose();  // row I of P^T: the fine points interpolating from I
  const auto m = static_cast<std::size_t>(p.cols());
  const std::int32_t *tp = pt.outerIndexPtr(), *ti = pt.innerIndexPtr(), *ap = a.outerIndexPtr(), *ai = a.innerIndexPtr();
  const std::int32_t *pp = p.outerIndexPtr(), *pi = p.innerIndexPtr();
  const double *tv = pt.valuePtr(), *av = a.valuePtr(), *pv = p.valuePtr();
  return rows_in_parallel(
      m, static_cast<Eigen::Index>(m), static_cast<std::size_t>(a.nonZeros()) * m / std::max<std::size_t>(1, static_cast<std::size_t>(a.rows())) + m,
      [&] { return RowAccumulator(m); },
      [&](std::size_t row, RowAccumulator& acc, std::vector<std::int32_t>& cols, std::vector<double>& vals) {
        // Row I of P^T A P = sum_i p_iI sum_k a_ik P[k, :].
        for (std::int32_t f = tp[row]; f < tp[row + 1]; ++f)
          for (std::int32_t e = ap[ti[f]]; e < ap[ti[f] + 1]; ++e) {
            const double w = tv[f] * av[e];
            for (std::int32_t c = pp[ai[e]]; c < pp[ai[e] + 1]; ++c) acc.add(pi[c], w * pv[c]);
          }
        std::sort(acc.touched.begin(), acc.touched.end());
        for (std::int32_t j : acc.touched) {
          cols.push_back(j);
          vals.push_back(acc.value[static_cast<std::size_t>(j)]);
          acc.value[static_cast<std::size_t>(j)] = 0.0;
          acc.seen[static_cast<std::size_t>(j)] = 0;
        }
        acc.touched.clear();
      });
}

SparseMatrix sparse_product(const SparseMatrix& a, const SparseMatrix& b, double prune) {
  const auto m = static_cast<std::size_t>(b.cols());
  const std::int32_t *ap = a.outerIndexPtr(), *ai = a.innerIndexPtr(), *bp = b.outerIndexPtr(), *bi = b.innerIndexPtr();
  const double *av = a.valuePtr(), *bv = b.valuePtr();
  return rows_in_parallel(
      static_cast<std::size_t>(a.rows()), b.cols(), static_cast<std::size_t>(a.nonZeros()) * 2,
      [&] { return RowAccumulator(m); },
      [&](std::size_t row, RowAccumulator& acc, std::vector<std::int32_t>& cols, std::vector<double>& vals) {
        for (std::int32_t e = ap[row]; e < ap[row + 1]; ++e)
          for (std::int32_t c = bp[ai[e]]; c < bp[ai[e] + 1]; ++c) acc.add(bi[c], av[e] * bv[c]);
        std::sort(acc.touched.begin(), acc.touched.end());
        // Pruning: drop entries below `prune` (never the largest) and rescale to the old row sum.
        double sum = 0, kept = 0, largest = 0;
        for (std::int32_t j : acc.touched) sum += acc.value[static_cast<std::size_t>(j)], largest = std::max(largest, acc.value[static_cast<std::size_t>(j)]);
        auto keep = [&](double v) { return !(prune > 0) || v >= prune || v == largest; };
        for (std::int32_t j : acc.touched)
          if (keep(acc.value[static_cast<std::size_t>(j)])) kept += acc.value[static_cast<std::size_t>(j)];
        const double scale = (prune > 0 && kept > 0) ? sum / kept : 1.0;
        for (std::int32_t j : acc.touched) {
          const double v = acc.value[static_cast<std::size_t>(j)];
          acc.value[static_cast<std::size_t>(j)] = 0.0;
          acc.seen[static_cast<std::size_t>(j)] = 0;
          if (keep(v)) cols.push_back(j), vals.push_back(v * scale);
        }
        acc.touched.clear();
      });
}

SparseMatrix scatter_rows(const SparseMatrix& m, const std::vector<std::uint32_t>& order) {
  const std::size_t n = order.size();
  std::vector<std::uint32_t> source(n);  // source[i] = row of m that becomes row i
  for (std::size_t r = 0; r < n; ++r) source[order[r]] = static_cast<std::uint32_t>(r);
  std::vector<std::int32_t> outer(n + 1, 0), inner;
  std::vector<double> values;
  inner.reserve(static_cast<std::size_t>(m.nonZeros()));
  values.reserve(static_cast<std::size_t>(m.nonZeros()));
  for (std::size_t i = 0; i < n; ++i) {
    for (SparseMatrix::InnerIterator it(m, static_cast<Eigen::Index>(source[i])); it; ++it)
      inner.push_back(static_cast<std::int32_t>(it.col())), values.push_back(it.value());
    outer[i + 1] = static_cast<std::int32_t>(values.size());
  }
  return from_rows(m.rows(), m.cols(), outer, inner, values);
}

}  // namespace qf
