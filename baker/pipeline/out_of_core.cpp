// The out-of-core bake's streaming parts: the scratch file in Morton tiles, the subsample, the
// links of full points to it, and the textures resampled from every point, tile by tile.
#include "pipeline/out_of_core.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <queue>
#include <stdexcept>

#include "analysis/neighborhoods.h"
#include "core/progress.h"

namespace qf {
namespace {

// ---------------------------------------------------------------------------------------------
// One tile's points as read back: the file's records, and the links once made.
struct TileData {
  std::vector<Vec3f> positions, normals;
  std::vector<float> radii;
  std::vector<Rgb8> colors;
  std::vector<std::uint32_t> link_index;  // kLinks per point
  std::vector<float> link_weight;
};

template <class T>
void append_array(ScratchFile& f, const std::vector<T>& v) {
  if (!v.empty()) f.append(v.data(), v.size() * sizeof(T));
}

template <class T>
std::uint64_t read_array(const ScratchFile& f, std::vector<T>& v, std::size_t n, std::uint64_t at) {
  v.resize(n);
  if (n) f.read(v.data(), n * sizeof(T), at);
  return at + n * sizeof(T);
}

void read_tile(const StreamedPoints& s, const StreamedPoints::Tile& t, TileData& out, bool links) {
  const std::size_t c = t.count;
  std::uint64_t at = read_array(*s.file, out.positions, c, t.offset);
  if (s.normals) at = read_array(*s.file, out.normals, c, at);
  if (s.radii) at = read_array(*s.file, out.radii, c, at);
  if (s.colors) read_array(*s.file, out.colors, c, at);
  if (links) read_array(*s.file, out.link_weight, c * kLinks, read_array(*s.file, out.link_index, c * kLinks, t.links_offset));
}

// A run of the external sort, or the points as they arrived: each record array in turn.
struct Extent {
  std::uint64_t offset = 0;
  std::size_t count = 0;
};

void append_records(ScratchFile& f, const StreamedPoints& s, const PointSet& p) {
  append_array(f, p.positions);
  if (s.normals) append_array(f, p.normals);
  if (s.radii) append_array(f, p.radii);
  if (s.colors) append_array(f, p.colors);
}

// Records [first, first + n) of an extent written by append_records (of e.count points).
void read_records(const ScratchFile& f, const StreamedPoints& s, const Extent& e, std::size_t first, std::size_t n, PointSet& out) {
  std::uint64_t at = e.offset;
  read_array(f, out.positions, n, at + first * sizeof(Vec3f));
  at += e.count * sizeof(Vec3f);
  if (s.normals) read_array(f, out.normals, n, at + first * sizeof(Vec3f)), at += e.count * sizeof(Vec3f);
  if (s.radii) read_array(f, out.radii, n, at + first * sizeof(float)), at += e.count * sizeof(float);
  if (s.colors) read_array(f, out.colors, n, at + first * sizeof(Rgb8));
}

template <class T>
void append_to(std::vector<T>& out, const std::vector<T>& v) {
  out.insert(out.end(), v.begin(), v.end());
}

// Spill step 1: the blocks as they come to `raw`, and what the set holds: its count, bounds,
// attributes (the first block's; a reader gives every block the same) and whether radii are missing.
std::vector<Extent> raw_blocks(const PointBlocks& blocks, ScratchFile& raw, StreamedPoints& s) {
  std::vector<Extent> out;
  bool first = true;
  s.needs_radii = false;
  blocks([&](PointSet& b) {
    if (b.size() == 0) return;
    if (first) s.normals = b.has_normals(), s.radii = b.has_radii(), s.colors = b.has_colors();
    if (b.has_normals() != s.normals || b.has_radii() != s.radii || b.has_colors() != s.colors)
      throw std::logic_error("spill_points: blocks with different attributes");
    first = false;
    s.needs_radii |= !s.radii || std::find(b.radii.begin(), b.radii.end(), 0.0f) != b.radii.end();
    for (const Vec3f& p : b.positions) s.bounds.add(p);
    out.push_back({raw.size(), b.size()});
    append_records(raw, s, b);
    s.points += b.size();
  });
  return out;
}

// Spill step 2: runs of at most `sort_points` points (whole blocks, at least one) read back,
// sorted by MortonKey in the whole set's box and written to `runs` with their keys (codes, then
// arrival indices) after the records.
std::vector<Extent> sorted_runs(const ScratchFile& raw, const std::vector<Extent>& blocks, std::size_t sort_points,
                                const StreamedPoints& s, ScratchFile& runs) {
  std::vector<Extent> out;
  std::uint64_t index = 0;  // arrival index of the run's first point
  for (std::size_t b = 0; b < blocks.size();) {
    std::size_t end = b, n = 0;
    while (end < blocks.size() && (end == b || n + blocks[end].count <= sort_points)) n += blocks[end++].count;
    progress::step("sorting points " + std::to_string(index) + " to " + std::to_string(index + n) + " of " + std::to_string(s.points) +
                   " in Morton order");
    PointSet run;
    run.positions.reserve(n);
    if (s.normals) run.normals.reserve(n);
    if (s.radii) run.radii.reserve(n);
    if (s.colors) run.colors.reserve(n);
    for (; b < end; ++b) {
      PointSet part;
      read_records(raw, s, blocks[b], 0, blocks[b].count, part);
      append_to(run.positions, part.positions), append_to(run.normals, part.normals);
      append_to(run.radii, part.radii), append_to(run.colors, part.colors);
    }
    std::vector<MortonKey> keys(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) {
      const Vec3f p = run.positions[static_cast<std::size_t>(i)];
      keys[static_cast<std::size_t>(i)] = {morton_code(p, s.bounds), p, index + static_cast<std::uint64_t>(i)};
    }
    std::sort(keys.begin(), keys.end());
    std::vector<std::uint32_t> order(n);
    std::vector<std::uint64_t> codes(n), indices(n);
    for (std::size_t i = 0; i < n; ++i)
      order[i] = static_cast<std::uint32_t>(keys[i].index - index), codes[i] = keys[i].code, indices[i] = keys[i].index;
    std::vector<MortonKey>().swap(keys);
    run = permuted(run, order);
    out.push_back({runs.size(), n});
    append_records(runs, s, run);
    append_array(runs, codes);
    append_array(runs, indices);
    index += n;
  }
  return out;
}

// One run's points in order, a buffer at a time.
class RunCursor {
 public:
  RunCursor(const ScratchFile& f, const StreamedPoints& s, const Extent& e, std::size_t buffer) : f_(&f), s_(&s), e_(e), buffer_(buffer) {
    fill();
  }
  bool done() const { return next_ >= e_.count; }
  MortonKey key() const { return {codes_[at_], buf_.positions[at_], indices_[at_]}; }
  // Appends the current point to `out` (the arrays the set holds) and moves on.
  void take(TileData& out) {
    out.positions.push_back(buf_.positions[at_]);
    if (s_->normals) out.normals.push_back(buf_.normals[at_]);
    if (s_->radii) out.radii.push_back(buf_.radii[at_]);
    if (s_->colors) out.colors.push_back(buf_.colors[at_]);
    ++next_;
    if (++at_ == buf_.positions.size() && !done()) fill();
  }

 private:
  void fill() {
    const std::size_t n = std::min(buffer_, e_.count - next_);
    read_records(*f_, *s_, e_, next_, n, buf_);
    const std::size_t record = sizeof(Vec3f) * (s_->normals ? 2 : 1) + (s_->radii ? sizeof(float) : 0) + (s_->colors ? sizeof(Rgb8) : 0);
    const std::uint64_t keys_at = e_.offset + e_.count * record;
    read_array(*f_, codes_, n, keys_at + next_ * sizeof(std::uint64_t));
    read_array(*f_, indices_, n, keys_at + (e_.count + next_) * sizeof(std::uint64_t));
    at_ = 0;
  }
  const ScratchFile* f_;
  const StreamedPoints* s_;
  Extent e_;
  std::size_t buffer_, next_ = 0, at_ = 0;
  PointSet buf_;
  std::vector<std::uint64_t> codes_, indices_;
};

// The subsample, picked as the merged points go by: stratum j holds the points
// [j n / m, (j + 1) n / m) of the Morton order, spatially compact runs of the same number of
// points, so the subsample follows the input's density as the in-memory bake sees it (an even
// voxel grid would thin dense parts more than sparse ones). Each stratum keeps its point nearest
// the stratum's centroid (a real point, with its own attributes; the first in Morton order on ties).
class StratumPicker {
 public:
  StratumPicker(const StreamedPoints& s, std::size_t m) : s_(s), n_(s.points), m_(m) {}
  void add(const TileData& t, std::size_t i) {
    stratum_.positions.push_back(t.positions[i]);
    if (s_.normals) stratum_.normals.push_back(t.normals[i]);
    if (s_.radii) stratum_.radii.push_back(t.radii[i]);
    if (s_.colors) stratum_.colors.push_back(t.colors[i]);
    if (++seen_ == (j_ + 1) * n_ / m_) pick();
  }
  PointSet take() { return std::move(out_); }

 private:
  void pick() {
    const std::vector<Vec3f>& p = stratum_.positions;
    double c[3] = {0, 0, 0};
    for (const Vec3f& v : p)
      for (int a = 0; a < 3; ++a) c[a] += v[a];
    const double k = double(p.size());
    const Vec3f centroid{float(c[0] / k), float(c[1] / k), float(c[2] / k)};
    std::size_t best = 0;
    float best_d = INFINITY;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3f v = p[i] - centroid;
      const float d = dot(v, v);
      if (d < best_d) best_d = d, best = i;
    }
    out_.positions.push_back(p[best]);
    if (s_.normals) out_.normals.push_back(stratum_.normals[best]);
    if (s_.radii) out_.radii.push_back(stratum_.radii[best]);
    if (s_.colors) out_.colors.push_back(stratum_.colors[best]);
    stratum_.positions.clear(), stratum_.normals.clear(), stratum_.radii.clear(), stratum_.colors.clear();
    ++j_;
  }
  const StreamedPoints& s_;
  std::size_t n_, m_, seen_ = 0, j_ = 0;
  TileData stratum_;
  PointSet out_;
};

// Spill step 3: the runs merged into the bake's file, in tiles of kTilePoints; the subsample
// picked on the way.
void merged_tiles(const ScratchFile& runs, const std::vector<Extent>& extents, std::size_t subsample, StreamedPoints& s) {
  constexpr std::size_t kCursorPoints = 1u << 15;
  std::vector<RunCursor> cursors;
  for (const Extent& e : extents) cursors.emplace_back(runs, s, e, kCursorPoints);
  using Head = std::pair<MortonKey, std::size_t>;
  const auto later = [](const Head& a, const Head& b) { return b.first < a.first; };
  std::priority_queue<Head, std::vector<Head>, decltype(later)> heads(later);
  for (std::size_t r = 0; r < cursors.size(); ++r)
    if (!cursors[r].done()) heads.push({cursors[r].key(), r});
  StratumPicker picker(s, subsample);
  progress::step("writing " + std::to_string(s.points) + " points to scratch in Morton order (" + s.file->path() + ")",
                 (s.points + kTilePoints - 1) / kTilePoints);
  for (std::size_t first = 0; first < s.points; first += kTilePoints) {
    StreamedPoints::Tile t;
    t.first = static_cast<std::uint32_t>(first);
    t.count = static_cast<std::uint32_t>(std::min(kTilePoints, s.points - first));
    TileData d;
    for (std::size_t i = 0; i < t.count; ++i) {
      const std::size_t r = heads.top().second;
      heads.pop();
      cursors[r].take(d);
      if (!cursors[r].done()) heads.push({cursors[r].key(), r});
      t.bounds.add(d.positions.back());
      picker.add(d, i);
    }
    t.offset = s.file->size();
    append_array(*s.file, d.positions);
    append_array(*s.file, d.normals);
    append_array(*s.file, d.radii);
    append_array(*s.file, d.colors);
    s.tiles.push_back(t);
    progress::advance();
  }
  s.subsample = picker.take();
}

}  // namespace

PointBlocks blocks_of(const PointSet& points) {
  return [&points](const std::function<void(PointSet&)>& each) {
    for (std::size_t first = 0; first < points.size(); first += kTilePoints) {
      std::vector<std::uint32_t> part(std::min(kTilePoints, points.size() - first));
      for (std::size_t i = 0; i < part.size(); ++i) part[i] = static_cast<std::uint32_t>(first + i);
      PointSet b = permuted(points, part);
      each(b);
    }
  };
}

StreamedPoints spill_points(const PointBlocks& blocks, const SpillOptions& o) {
  StreamedPoints s;
  s.file = std::make_unique<ScratchFile>("bake", o.scratch_dir);
  std::vector<Extent> runs;
  auto run_file = std::make_unique<ScratchFile>("sort", o.scratch_dir);
  {
    // 1. The blocks as they come, then 2. sorted in runs; the raw file goes once sorted.
    ScratchFile raw("read", o.scratch_dir);
    progress::step("reading points to scratch (" + raw.path() + ")");
    const std::vector<Extent> arrived = raw_blocks(blocks, raw, s);
    if (s.points == 0) throw std::logic_error("spill_points: no points");
    runs = sorted_runs(raw, arrived, std::max<std::size_t>(1, o.sort_points), s, *run_file);
    s.scratch_peak = raw.size() + run_file->size();
  }
  // 3. The runs merged into tiles, the subsample picked on the way.
  const std::size_t m = std::clamp<std::size_t>(o.subsample, 1, s.points);
  s.stride = double(s.points) / double(m);
  merged_tiles(*run_file, runs, m, s);
  s.scratch_peak = std::max<std::uint64_t>(s.scratch_peak, run_file->size() + s.file->size());
  run_file.reset();
  // 4. The subsample's radii at the full density where the input has none.
  if (s.needs_radii) {
    PointSet own;
    own.positions = s.subsample.positions;
    estimate_radii(own);
    const float scale = 1.0f / static_cast<float>(std::sqrt(s.stride));
    if (s.subsample.radii.empty()) s.subsample.radii.assign(m, 0.0f);
    for (std::size_t j = 0; j < m; ++j)
      if (s.subsample.radii[j] == 0.0f) s.subsample.radii[j] = own.radii[j] * scale;
  }
  return s;
}

namespace {

// A point's weights over its `found` nearest subsample points (squared distances d2, nearest
// first): inverse-square-distance (Shepard's), which interpolate, so a point of the subsample
// takes exactly its own functions (coincident ones share equally) and a subsample of every point
// gives the in-memory bake's alpha. Unused slots repeat the first index and weigh nothing.
// Returns the distance to the farthest linked point.
float link_weights(int found, std::uint32_t* idx, const float* d2, float* w) {
  int zeros = 0;
  while (zeros < found && d2[zeros] == 0.0f) ++zeros;
  double sum = 0;
  for (int q = 0; q < found; ++q) sum += zeros ? (q < zeros ? 1.0 : 0.0) : 1.0 / double(d2[q]);
  for (int q = 0; q < found; ++q) w[q] = static_cast<float>((zeros ? (q < zeros ? 1.0 : 0.0) : 1.0 / double(d2[q])) / sum);
  for (int q = found; q < kLinks; ++q) idx[q] = idx[0], w[q] = 0.0f;
  return std::sqrt(d2[found - 1]);
}

}  // namespace

std::size_t drop_subsample_outliers(StreamedPoints& s, float factor) {
  OutlierOptions o;
  o.factor = factor;
  s.outlier_limit = INFINITY;
  return drop_outliers(s.subsample, o, &s.outlier_limit);
}

std::size_t link_points(StreamedPoints& s) {
  // FLANN's kd-tree (analysis/neighborhoods.h): a uniform grid of the subsample's median spacing
  // took 10+ minutes on the scan-like set, whose density varies 100-fold and whose outliers lie
  // hundreds of cells from any other point.
  const NearestPoints tree(s.subsample.positions);
  progress::step("linking " + std::to_string(s.points) + " points to the subsample", s.tiles.size());
  // A point is an outlier where the mean distance to its kLinks nearest passes the limit, which is
  // sure once the farthest of them is past kLinks x the limit: the search looks no farther, so the
  // strays far from every subsample point (dropped from it) cost no more than the others.
  const float bound = std::isinf(s.outlier_limit) ? INFINITY : kLinks * s.outlier_limit;
  TileData d;
  std::size_t outliers = 0;
  for (StreamedPoints::Tile& t : s.tiles) {
    read_tile(s, t, d, false);
    const std::size_t c = t.count;
    d.link_index.assign(c * kLinks, 0);
    d.link_weight.assign(c * kLinks, 0.0f);
    std::vector<float> dist2(c * kLinks, 0.0f);
    float reach = 0;
    // Blocks of consecutive points (the tile is in Morton order: nearby queries touch nearby nodes).
    constexpr std::size_t kBlock = 512;
    const std::ptrdiff_t blocks = static_cast<std::ptrdiff_t>((c + kBlock - 1) / kBlock);
#pragma omp parallel for schedule(dynamic) reduction(max : reach) reduction(+ : outliers)
    for (std::ptrdiff_t b = 0; b < blocks; ++b) {
      const std::size_t first = static_cast<std::size_t>(b) * kBlock, count = std::min(kBlock, c - first);
      const int found = tree.nearest(&d.positions[first], count, kLinks, &d.link_index[first * kLinks], &dist2[first * kLinks], bound * bound);
      for (std::size_t i = first; i < first + count; ++i) {
        double mean = 0;  // nearest first: the same sum whatever the thread
        for (int q = 0; q < found; ++q) mean += std::sqrt(double(dist2[i * kLinks + static_cast<std::size_t>(q)]));
        if (mean / found > double(s.outlier_limit)) {
          ++outliers;  // linked to nothing: weights stay 0
          for (int q = 1; q < kLinks; ++q) d.link_index[i * kLinks + static_cast<std::size_t>(q)] = d.link_index[i * kLinks];
          continue;
        }
        reach = std::max(reach, link_weights(found, &d.link_index[i * kLinks], &dist2[i * kLinks], &d.link_weight[i * kLinks]));
      }
    }
    t.reach = reach;
    t.links_offset = s.file->size();
    append_array(*s.file, d.link_index);
    append_array(*s.file, d.link_weight);
    progress::advance();
  }
  return outliers;
}

namespace {

// A quad's full-density points, gathered from the tiles for its texture.
struct QuadPoints {
  std::vector<Vec3f> positions, normals;
  std::vector<float> radii;
  std::vector<Rgb8> colors;
  std::vector<double> alpha, psi;  // its alpha (domain_partition's) and its function's value
  void reserve(double estimate, const StreamedPoints& s, const std::vector<Vec3f>& sub_normals) {
    const auto n = static_cast<std::size_t>(estimate);
    positions.reserve(n), radii.reserve(n), alpha.reserve(n), psi.reserve(n);
    if (s.colors) colors.reserve(n);
    if (s.normals || !sub_normals.empty()) normals.reserve(n);
  }
  void fit() {
    positions.shrink_to_fit(), normals.shrink_to_fit(), radii.shrink_to_fit(), colors.shrink_to_fit();
    alpha.shrink_to_fit(), psi.shrink_to_fit();
  }
};

// One point's membership: quad (index into rects), alpha and the function's value.
struct Member {
  std::uint32_t point, quad;
  double alpha, psi;
};

// The memberships of one point from its links: Psi_full(x) = sum_q w_q Psi_sub(link_q), then the
// domain rule (domains.h) and domain_partition's renormalisation over every domain it is in
// (functions with a rectangle: quad_of >= 0); kept for the batch's quads (batch_of >= 0) only.
void point_members(const SparseMatrix& psi, const std::uint32_t* idx, const float* w, const std::vector<std::int32_t>& quad_of,
                   const std::vector<std::int32_t>& batch_of, const DomainOptions& o, std::uint32_t point,
                   std::vector<std::pair<std::int32_t, double>>& row, std::vector<Member>& out) {
  row.clear();
  for (int q = 0; q < kLinks; ++q) {
    if (!(w[q] > 0)) continue;
    for (SparseMatrix::InnerIterator it(psi, static_cast<Eigen::Index>(idx[q])); it; ++it) row.push_back({it.col(), double(w[q]) * it.value()});
  }
  if (row.empty()) return;
  // Summed per function in link order (stable), so the sums do not depend on anything else.
  std::stable_sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::size_t u = 0;
  for (std::size_t e = 1; e < row.size(); ++e) {
    if (row[e].first == row[u].first) row[u].second += row[e].second;
    else row[++u] = row[e];
  }
  row.resize(u + 1);
  if (o.strict) {
    std::size_t best = 0;
    for (std::size_t e = 1; e < row.size(); ++e)
      if (row[e].second > row[best].second) best = e;
    if (batch_of[static_cast<std::size_t>(row[best].first)] >= 0)
      out.push_back({point, static_cast<std::uint32_t>(batch_of[static_cast<std::size_t>(row[best].first)]), 1.0, row[best].second});
    return;
  }
  double sum = 0;
  for (const auto& [f, v] : row)
    if (v > o.tau && quad_of[static_cast<std::size_t>(f)] >= 0) sum += v;
  if (!(sum > 0)) return;
  for (const auto& [f, v] : row)
    if (v > o.tau && batch_of[static_cast<std::size_t>(f)] >= 0)
      out.push_back({point, static_cast<std::uint32_t>(batch_of[static_cast<std::size_t>(f)]), v / sum, v});
}

// Per quad, the box its full-density points can come from: the subsample points where its function
// is non-zero (a full point in the domain has one of them among its links).
std::vector<Bounds> function_bounds(const SparseMatrix& psi, const std::vector<Vec3f>& sub, const std::vector<std::int32_t>& quad_of,
                                    std::size_t quads) {
  std::vector<Bounds> b(quads);
  for (Eigen::Index j = 0; j < psi.rows(); ++j)
    for (SparseMatrix::InnerIterator it(psi, j); it; ++it)
      if (it.value() > 0 && quad_of[static_cast<std::size_t>(it.col())] >= 0)
        b[static_cast<std::size_t>(quad_of[static_cast<std::size_t>(it.col())])].add(sub[static_cast<std::size_t>(j)]);
  return b;
}

bool overlaps(const Bounds& a, const Bounds& b, float pad) {
  if (a.empty() || b.empty()) return false;
  for (int k = 0; k < 3; ++k)
    if (a.min[k] - pad > b.max[k] || b.min[k] - pad > a.max[k]) return false;
  return true;
}

// The quads in batches of about `batch_points` estimated full points (a domain's subsample points
// x the stride), in the order of their rectangles' centres along the Morton curve so that a batch
// reads nearby tiles; a quad larger than a batch is a batch of its own.
std::vector<std::vector<std::uint32_t>> quad_batches(const StreamedPoints& s, const Domains& d, const std::vector<SupportRect>& rects,
                                                     std::size_t batch_points) {
  std::vector<Vec3f> centers;
  for (const SupportRect& r : rects) centers.push_back(r.center);
  const std::vector<std::uint32_t> order = centers.empty() ? std::vector<std::uint32_t>() : morton_order(centers);
  std::vector<std::vector<std::uint32_t>> batches;
  double held = 0;
  for (std::uint32_t q : order) {
    const double est = double(d.size(rects[q].domain)) * s.stride;
    if (batches.empty() || (held + est > double(batch_points) && !batches.back().empty())) {
      batches.emplace_back();
      held = 0;
    }
    batches.back().push_back(q);
    held += est;
  }
  return batches;
}

// Gathers the batch's quads' points from every tile that may reach them.
void gather_batch(const StreamedPoints& s, const std::vector<Vec3f>& sub_normals, const SparseMatrix& psi,
                  const std::vector<std::int32_t>& quad_of, const std::vector<std::int32_t>& batch_of, const std::vector<Bounds>& reach,
                  const DomainOptions& o, std::vector<QuadPoints>& quads) {
  constexpr std::size_t kChunk = 4096;  // fixed chunks: the same order of members at any thread count
  // The subsample points where a function of the batch is non-zero: a point none of whose links is
  // one can be in none of the batch's domains, and is passed over without making its row (most
  // of them, the batches being spatially compact: the 1M-point torus' textures took 18 s a level
  // with every row made in each of 6 batches).
  std::vector<char> touches(static_cast<std::size_t>(psi.rows()), 0);
  for (Eigen::Index j = 0; j < psi.rows(); ++j)
    for (SparseMatrix::InnerIterator it(psi, j); it; ++it)
      if (batch_of[static_cast<std::size_t>(it.col())] >= 0) touches[static_cast<std::size_t>(j)] = 1;
  TileData d;
  std::vector<std::vector<Member>> chunks;
  for (const StreamedPoints::Tile& t : s.tiles) {
    bool wanted = false;
    for (std::size_t q = 0; q < quads.size() && !wanted; ++q)
      wanted = overlaps(t.bounds, reach[q], t.reach);
    if (!wanted) {
      progress::advance();
      continue;
    }
    read_tile(s, t, d, true);
    const std::size_t c = t.count;
    chunks.assign((c + kChunk - 1) / kChunk, {});
#pragma omp parallel
    {
      std::vector<std::pair<std::int32_t, double>> row;
#pragma omp for schedule(dynamic, 1)
      for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(chunks.size()); ++k)
        for (std::size_t i = static_cast<std::size_t>(k) * kChunk; i < std::min(c, (static_cast<std::size_t>(k) + 1) * kChunk); ++i) {
          bool near = false;
          for (int q = 0; q < kLinks && !near; ++q) near = d.link_weight[i * kLinks + q] > 0 && touches[d.link_index[i * kLinks + q]];
          if (near)
            point_members(psi, &d.link_index[i * kLinks], &d.link_weight[i * kLinks], quad_of, batch_of, o, static_cast<std::uint32_t>(i),
                          row, chunks[static_cast<std::size_t>(k)]);
        }
    }
    for (const std::vector<Member>& chunk : chunks)
      for (const Member& m : chunk) {
        QuadPoints& p = quads[m.quad];
        const std::size_t i = m.point;
        const std::uint32_t* idx = &d.link_index[i * kLinks];
        const float* w = &d.link_weight[i * kLinks];
        p.positions.push_back(d.positions[i]);
        p.alpha.push_back(m.alpha);
        p.psi.push_back(m.psi);
        if (s.colors) p.colors.push_back(d.colors[i]);
        // A radius of its own, else its links' (at the full density); a normal of its own, else
        // its links' (the subsample's estimated normals, oriented alike), renormalised.
        float r = s.radii ? d.radii[i] : 0.0f;
        if (r == 0.0f)
          for (int q = 0; q < kLinks; ++q) r += w[q] * s.subsample.radii[idx[q]];
        p.radii.push_back(r);
        if (s.normals) {
          p.normals.push_back(d.normals[i]);
        } else if (!sub_normals.empty()) {
          Vec3f n{};
          for (int q = 0; q < kLinks; ++q) n = n + sub_normals[idx[q]] * w[q];
          p.normals.push_back(normalized(n, sub_normals[idx[0]]));
        }
      }
    progress::advance();
  }
}

}  // namespace

std::vector<Texture> streamed_textures(const StreamedPoints& s, const std::vector<Vec3f>& sub_normals, const SparseMatrix& psi,
                                       const Domains& d, std::vector<SupportRect>& rects, const DomainOptions& domains,
                                       const SupportOptions& support, const TextureOptions& texture, std::size_t batch_points,
                                       std::size_t* batch_count) {
  std::vector<std::int32_t> quad_of(static_cast<std::size_t>(psi.cols()), -1);  // function -> rectangle
  for (std::size_t q = 0; q < rects.size(); ++q) quad_of[rects[q].domain] = static_cast<std::int32_t>(q);
  const std::vector<Bounds> all_reach = function_bounds(psi, s.subsample.positions, quad_of, rects.size());
  const std::vector<std::vector<std::uint32_t>> batches = quad_batches(s, d, rects, batch_points);
  if (batch_count) *batch_count = batches.size();
  std::vector<Texture> textures(rects.size());
  for (std::size_t b = 0; b < batches.size(); ++b) {
    const std::vector<std::uint32_t>& batch = batches[b];
    // 1. The batch's points: this batch's quads only (the others map to -1 here).
    std::vector<std::int32_t> local(quad_of.size(), -1);
    std::vector<Bounds> reach;
    for (std::size_t k = 0; k < batch.size(); ++k) {
      local[rects[batch[k]].domain] = static_cast<std::int32_t>(k);
      reach.push_back(all_reach[batch[k]]);
    }
    progress::step("reading " + std::to_string(s.tiles.size()) + " tiles for " + std::to_string(batch.size()) + " quads (batch " +
                       std::to_string(b + 1) + " of " + std::to_string(batches.size()) + ")",
                   s.tiles.size());
    // Each quad's room reserved for its estimated points and 10% more, then fitted: growing by
    // doubling could hold twice the batch's points at its end (the plan counts each member once).
    std::vector<QuadPoints> points(batch.size());
    for (std::size_t k = 0; k < batch.size(); ++k) points[k].reserve(1.1 * double(d.size(rects[batch[k]].domain)) * s.stride, s, sub_normals);
    gather_batch(s, sub_normals, psi, quad_of, local, reach, domains, points);
    for (QuadPoints& p : points) p.fit();
    // 2. Their rectangles and textures, largest first (as the in-memory bake's level_textures),
    //    each from its own points as a one-domain set; a quad's points are freed once done.
    std::vector<std::size_t> by_size(batch.size());
    for (std::size_t k = 0; k < by_size.size(); ++k) by_size[k] = k;
    std::stable_sort(by_size.begin(), by_size.end(), [&](std::size_t x, std::size_t y) { return points[x].positions.size() > points[y].positions.size(); });
    progress::step("textures of " + std::to_string(batch.size()) + " quads (batch " + std::to_string(b + 1) + " of " +
                       std::to_string(batches.size()) + ")",
                   batch.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::ptrdiff_t q = 0; q < static_cast<std::ptrdiff_t>(by_size.size()); ++q) {
      const std::size_t k = by_size[static_cast<std::size_t>(q)];
      QuadPoints& p = points[k];
      SupportRect& rect = rects[batch[k]];
      const std::size_t n = p.positions.size();
      if (n > 0) {
        Domains one;
        one.offsets = std::vector<std::uint32_t>{0, static_cast<std::uint32_t>(n)};  // (moved in: GCC 12 warns on assign)
        one.points.resize(n);
        std::vector<std::int32_t> outer(n + 1), inner(n, 0);
        for (std::size_t i = 0; i < n; ++i) one.points[i] = static_cast<std::uint32_t>(i), outer[i] = static_cast<std::int32_t>(i);
        outer[n] = static_cast<std::int32_t>(n);
        // The rectangle again from every point of the domain, as the in-memory bake makes it
        // (support_rectangles: weighted plane, extent with every splat, mean radius): the
        // subsample's reaches up to its spacing short of the domain's outermost points, and its
        // texture would clip their splats.
        // (Each copy freed once made or used: a quad may hold millions of points.)
        {
          const SparseMatrix weights = from_rows(static_cast<Eigen::Index>(n), 1, outer, inner, p.psi);
          p.psi = {};
          const std::vector<SupportRect> full = support_rectangles(p.positions, p.normals, p.radii, weights, one, support);
          if (full.size() == 1) {
            const std::uint32_t domain = rect.domain;
            rect = full[0];
            rect.domain = domain;
          }
        }
        const SparseMatrix alpha = from_rows(static_cast<Eigen::Index>(n), 1, outer, inner, p.alpha);
        p.alpha = {};
        outer = {}, inner = {};
        SupportRect local_rect = rect;
        local_rect.domain = 0;
        textures[batch[k]] = resample_texture(p.positions, p.colors, p.normals, p.radii, alpha, one, local_rect, texture);
      } else {
        // No point of the whole set passed tau for this function (its subsample points did):
        // the subsample's rectangle, an empty texture of its size.
        Domains none;
        none.offsets = std::vector<std::uint32_t>{0, 0};
        SupportRect local_rect = rect;
        local_rect.domain = 0;
        textures[batch[k]] = resample_texture({}, {}, {}, {}, SparseMatrix(0, 1), none, local_rect, texture);
      }
      p = QuadPoints{};
      progress::advance();
    }
  }
  return textures;
}

}  // namespace qf
