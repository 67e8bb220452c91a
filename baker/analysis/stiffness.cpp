// Stiffness assembly (paper 2.2, eqs. 5-7): per-point fan contributions, then symmetrisation and
// the zero-row-sum diagonal, built directly in compressed row storage.
#include "analysis/stiffness.h"

#include <algorithm>
#include <cmath>

namespace qf {
namespace {

struct Entry {
  std::uint32_t col;
  double value;
};

// cot of the angle at c in triangle (a, b, c), from double-precision edge vectors.
// Returns false for a (near) zero-area triangle.
bool cotangent(const Vec3f& a, const Vec3f& b, const Vec3f& c, double& cot) {
  const double ux = double(a.x) - c.x, uy = double(a.y) - c.y, uz = double(a.z) - c.z;
  const double vx = double(b.x) - c.x, vy = double(b.y) - c.y, vz = double(b.z) - c.z;
  const double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
  const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
  cot = (ux * vx + uy * vy + uz * vz) / cross;
  return cross > 0 && std::isfinite(cot);
}

double longest_edge2(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  return std::max({double(dot(a - b, a - b)), double(dot(b - c, b - c)), double(dot(c - a, c - a))});
}

// Step 1 (eq. 5): row i of At from point i's own fan.
void fan_row(std::size_t i, const std::vector<Vec3f>& pos, const Fans& fans, const std::vector<float>& cls,
             std::vector<Entry>& row, std::size_t& zero_area) {
  row.clear();
  const Vec3f& pi = pos[i];
  for (std::uint32_t t = fans.offsets[i]; t < fans.offsets[i + 1]; ++t) {
    const std::uint32_t a = fans.triangles[t][0], b = fans.triangles[t][1];
    const Vec3f &pa = pos[a], &pb = pos[b];
    // |T| grad(Phi_i).grad(Phi_a) = -cot(angle at b) / 2, and likewise for b.
    double cot_a, cot_b;
    const double area2 = 0.5 * length(cross(pa - pi, pb - pi));  // area, for the degeneracy test only
    if (!(area2 > 1e-12 * longest_edge2(pi, pa, pb)) || !cotangent(pi, pa, pb, cot_b) || !cotangent(pi, pb, pa, cot_a)) {
      ++zero_area;
      continue;
    }
    const double c = (double(cls[i]) + cls[a] + cls[b]) / 3.0;  // C(T): mean of the nodal classifiers
    row.push_back({a, -0.5 * c * cot_b});
    row.push_back({b, -0.5 * c * cot_a});
  }
  // Merge the two contributions of each neighbour (it sits in two adjacent triangles).
  std::sort(row.begin(), row.end(), [](const Entry& x, const Entry& y) { return x.col < y.col; });
  std::size_t w = 0;
  for (std::size_t r = 0; r < row.size(); ++r) {
    if (w > 0 && row[w - 1].col == row[r].col) row[w - 1].value += row[r].value;
    else row[w++] = row[r];
  }
  row.resize(w);
}

}  // namespace

SparseMatrix assemble_stiffness(const std::vector<Vec3f>& positions, const Fans& fans,
                                const std::vector<float>& classifier, StiffnessReport* report) {
  const std::size_t n = positions.size();
  // 1. At, row by row in parallel: chunks of rows handed out dynamically, joined in row order
  //    (thread-count independent).
  constexpr std::size_t kChunk = 2048;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::int32_t> outer(n + 1, 0);
  std::vector<std::vector<Entry>> blocks(chunks);
  std::size_t zero_area = 0;
#pragma omp parallel reduction(+ : zero_area)
  {
    std::vector<Entry> row;
#pragma omp for schedule(dynamic)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(chunks); ++c) {
      auto& out = blocks[static_cast<std::size_t>(c)];
      out.reserve(7 * kChunk + 64);  // ~6 neighbours a row
      const std::size_t first = static_cast<std::size_t>(c) * kChunk, last = std::min(n, first + kChunk);
      for (std::size_t i = first; i < last; ++i) {
        fan_row(i, positions, fans, classifier, row, zero_area);
        outer[i + 1] = static_cast<std::int32_t>(row.size());
        out.insert(out.end(), row.begin(), row.end());
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) outer[i + 1] += outer[i];
  // Straight into the matrix, each block freed once copied (no intermediate arrays: the peak of
  // this step is the blocks and At, not three copies of the entries).
  SparseMatrix at(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  at.resizeNonZeros(static_cast<Eigen::Index>(outer[n]));
  std::copy(outer.begin(), outer.end(), at.outerIndexPtr());
  std::vector<std::int32_t>().swap(outer);
  std::int32_t* inner = at.innerIndexPtr();
  double* values = at.valuePtr();
  for (auto& blk : blocks) {
    for (const Entry& e : blk) *inner++ = static_cast<std::int32_t>(e.col), *values++ = e.value;
    std::vector<Entry>().swap(blk);
  }

  // 2. Eqs. 6-7: A_ij = (At_ij + At_ji) / 2, A_ii = -sum_j A_ij (exactly symmetric, rows sum to 0).
  SymmetrizeReport sym;
  SparseMatrix a = symmetrize_zero_row_sums(at, 0.0, &sym);
  if (report) {
    report->zero_area_triangles = zero_area;
    report->empty_rows = sym.empty_rows;
    report->one_sided_pairs = sym.one_sided;
  }
  return a;
}

}  // namespace qf
