// Shared sparse-matrix operations: symmetrisation with zero row sums, Galerkin product.
#include "core/sparse.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace qf {

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
  std::vector<std::int32_t> outer(n + 1, 0), inner;
  std::vector<double> values;
  inner.reserve(static_cast<std::size_t>(a.nonZeros()) + n);
  values.reserve(inner.capacity());
  std::size_t one_sided = 0, empty_rows = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    SparseMatrix::InnerIterator p(a, row), q(t, row);
    const std::size_t start = values.size();
    double sum = 0;
    bool diag_done = false;
    auto put_diagonal_before = [&](Eigen::Index col) {
      if (!diag_done && col > row) {
        inner.push_back(static_cast<std::int32_t>(i));
        values.push_back(0.0);  // set below
        diag_done = true;
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
      one_sided += (cp != cq);
      const double v = 0.5 * (x + y);
      if (v == 0.0 || std::fabs(v) <= drop * std::max(diag[i], diag[static_cast<std::size_t>(col)])) continue;
      put_diagonal_before(col);
      inner.push_back(static_cast<std::int32_t>(col));
      values.push_back(v);
      sum += v;
    }
    put_diagonal_before(a.cols());
    for (std::size_t r = start; r < values.size(); ++r)
      if (inner[r] == static_cast<std::int32_t>(i)) values[r] = -sum;
    empty_rows += values.size() - start == 1;
    outer[i + 1] = static_cast<std::int32_t>(values.size());
  }
  if (report) report->one_sided = one_sided / 2, report->empty_rows = empty_rows;
  return from_rows(a.rows(), a.cols(), outer, inner, values);
}

SparseMatrix galerkin_product(const SparseMatrix& a, const SparseMatrix& p) {
  const SparseMatrix pt = p.transpose();  // row I of P^T: the fine points interpolating from I
  const auto m = static_cast<std::size_t>(p.cols());
  std::vector<std::int32_t> outer(m + 1, 0);
  std::vector<std::vector<std::int32_t>> block_cols;
  std::vector<std::vector<double>> block_vals;
  // Each thread takes a contiguous block of coarse rows; rows are joined in order afterwards.
#pragma omp parallel
  {
#pragma omp single
    {
      block_cols.resize(static_cast<std::size_t>(omp_get_num_threads()));
      block_vals.resize(block_cols.size());
    }
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    // Galerkin rows hold about as many entries as A's rows: reserve once (growth copies into
    // fresh pages are slow on these machines).
    const std::size_t per_row = static_cast<std::size_t>(a.nonZeros()) / std::max<std::size_t>(1, static_cast<std::size_t>(a.rows())) + 4;
    block_cols[t].reserve(per_row * (m / block_cols.size() + 1));
    block_vals[t].reserve(per_row * (m / block_cols.size() + 1));
    std::vector<double> acc(m, 0.0);          // dense accumulator of one coarse row
    std::vector<std::int32_t> touched;
    std::vector<char> seen(m, 0);
    const std::int32_t *tp = pt.outerIndexPtr(), *ti = pt.innerIndexPtr();
    const double* tv = pt.valuePtr();
    const std::int32_t *ap = a.outerIndexPtr(), *ai = a.innerIndexPtr();
    const double* av = a.valuePtr();
    const std::int32_t *pp = p.outerIndexPtr(), *pi = p.innerIndexPtr();
    const double* pv = p.valuePtr();
#pragma omp for schedule(static)
    for (std::ptrdiff_t si = 0; si < static_cast<std::ptrdiff_t>(m); ++si) {
      touched.clear();
      // Row I of P^T A P = sum_i p_iI sum_k a_ik P[k, :].
      for (std::int32_t f = tp[si]; f < tp[si + 1]; ++f) {
        const std::int32_t i = ti[f];
        for (std::int32_t e = ap[i]; e < ap[i + 1]; ++e) {
          const double w = tv[f] * av[e];
          const std::int32_t k = ai[e];
          for (std::int32_t c = pp[k]; c < pp[k + 1]; ++c) {
            const auto j = static_cast<std::size_t>(pi[c]);
            if (!seen[j]) seen[j] = 1, touched.push_back(static_cast<std::int32_t>(j));
            acc[j] += w * pv[c];
          }
        }
      }
      std::sort(touched.begin(), touched.end());
      auto& cols = block_cols[t];
      auto& vals = block_vals[t];
      for (std::int32_t j : touched) {
        cols.push_back(j);
        vals.push_back(acc[static_cast<std::size_t>(j)]);
        acc[static_cast<std::size_t>(j)] = 0.0;
        seen[static_cast<std::size_t>(j)] = 0;
      }
      outer[static_cast<std::size_t>(si) + 1] = static_cast<std::int32_t>(touched.size());
    }
  }
  for (std::size_t i = 0; i < m; ++i) outer[i + 1] += outer[i];
  std::vector<std::int32_t> inner;
  std::vector<double> values;
  inner.reserve(static_cast<std::size_t>(outer[m]));
  values.reserve(static_cast<std::size_t>(outer[m]));
  for (std::size_t t = 0; t < block_cols.size(); ++t) {
    inner.insert(inner.end(), block_cols[t].begin(), block_cols[t].end());
    values.insert(values.end(), block_vals[t].begin(), block_vals[t].end());
  }
  return from_rows(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m), outer, inner, values);
}

SparseMatrix sparse_product(const SparseMatrix& a, const SparseMatrix& b, double prune) {
  const auto n = static_cast<std::size_t>(a.rows()), m = static_cast<std::size_t>(b.cols());
  std::vector<std::int32_t> outer(n + 1, 0);
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
    std::vector<double> acc(m, 0.0);
    std::vector<std::int32_t> touched;
    std::vector<char> seen(m, 0);
    const std::int32_t *ap = a.outerIndexPtr(), *ai = a.innerIndexPtr(), *bp = b.outerIndexPtr(), *bi = b.innerIndexPtr();
    const double *av = a.valuePtr(), *bv = b.valuePtr();
#pragma omp for schedule(static)
    for (std::ptrdiff_t si = 0; si < static_cast<std::ptrdiff_t>(n); ++si) {
      touched.clear();
      for (std::int32_t e = ap[si]; e < ap[si + 1]; ++e)
        for (std::int32_t c = bp[ai[e]]; c < bp[ai[e] + 1]; ++c) {
          const auto j = static_cast<std::size_t>(bi[c]);
          if (!seen[j]) seen[j] = 1, touched.push_back(static_cast<std::int32_t>(j));
          acc[j] += av[e] * bv[c];
        }
      std::sort(touched.begin(), touched.end());
      double sum = 0, kept = 0, largest = 0;
      for (std::int32_t j : touched) sum += acc[static_cast<std::size_t>(j)], largest = std::max(largest, acc[static_cast<std::size_t>(j)]);
      for (std::int32_t j : touched) {
        const double v = acc[static_cast<std::size_t>(j)];
        if (!(prune > 0) || v >= prune || v == largest) kept += v;
      }
      const double scale = (prune > 0 && kept > 0) ? sum / kept : 1.0;
      std::size_t count = 0;
      for (std::int32_t j : touched) {
        const double v = acc[static_cast<std::size_t>(j)];
        acc[static_cast<std::size_t>(j)] = 0.0;
        seen[static_cast<std::size_t>(j)] = 0;
        if (prune > 0 && v < prune && v != largest) continue;
        block_cols[t].push_back(j);
        block_vals[t].push_back(v * scale);
        ++count;
      }
      outer[static_cast<std::size_t>(si) + 1] = static_cast<std::int32_t>(count);
    }
  }
  for (std::size_t i = 0; i < n; ++i) outer[i + 1] += outer[i];
  std::vector<std::int32_t> inner;
  std::vector<double> values;
  inner.reserve(static_cast<std::size_t>(outer[n]));
  values.reserve(static_cast<std::size_t>(outer[n]));
  for (std::size_t t = 0; t < block_cols.size(); ++t) {
    inner.insert(inner.end(), block_cols[t].begin(), block_cols[t].end());
    values.insert(values.end(), block_vals[t].begin(), block_vals[t].end());
  }
  return from_rows(a.rows(), b.cols(), outer, inner, values);
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
