// QSplat .qs writer: builds the bounding-sphere tree of qsplat_make (§2.5) and writes it in the
// original's layout (§7.3 writer checklist), so that the original viewer reads our files.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <ostream>

#include "core/error.h"
#include "core/file_io.h"
#include "io/model_io.h"
#include "io/qsplat_codec.h"

namespace qf {
namespace {

struct Node {
  float center[3];
  float radius;
  Vec3f normal;
  float cone;  // half-angle, radians
  Rgb8 color;
  std::uint32_t first_child = 0;  // children are nodes[first_child .. first_child + child_count)
  std::uint8_t child_count = 0;
  bool has_grandchildren = false;
};

class TreeBuilder {
 public:
  explicit TreeBuilder(const PointSet& p) : pts_(p), order_(p.size()) {
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<std::uint32_t>(i);
  }

  // Returns the nodes with the root at index 0; the children of a node are contiguous.
  // Afterwards leaf_order() lists the input indices in depth-first leaf order.
  std::vector<Node> build() {
    nodes_.reserve(2 * order_.size() + 1);
    nodes_.emplace_back();
    fill(0, 0, order_.size());
    return std::move(nodes_);
  }
  const std::vector<std::uint32_t>& leaf_order() const { return order_; }

 private:
  using Range = std::pair<std::size_t, std::size_t>;  // [begin, end) in order_

  // §2.5: a range of at most 4 points has one leaf child per point. A bigger range is split at the
  // midpoint of its bounding box's longest axis; each half of at most 4 points is one child, a
  // bigger half is split once more and gives two children. So every node has 2 to 4 children.
  std::vector<Range> child_ranges(std::size_t b, std::size_t e) {
    std::vector<Range> out;
    if (e - b <= 4) {
      for (std::size_t i = b; i < e; ++i) out.push_back({i, i + 1});
      return out;
    }
    const std::size_t m = split(b, e);
    for (const Range& half : {Range{b, m}, Range{m, e}}) {
      if (half.second - half.first <= 4) {
        out.push_back(half);
      } else {
        const std::size_t mm = split(half.first, half.second);
        out.push_back({half.first, mm});
        out.push_back({mm, half.second});
      }
    }
    return out;
  }

  // Makes node `id` the interior node of order_[b, e).
  void fill(std::uint32_t id, std::size_t b, std::size_t e) {
    const std::vector<Range> ranges = child_ranges(b, e);
    const auto first = static_cast<std::uint32_t>(nodes_.size());
    nodes_.resize(nodes_.size() + ranges.size());
    for (std::size_t k = 0; k < ranges.size(); ++k) {
      const auto child = static_cast<std::uint32_t>(first + k);
      if (ranges[k].second - ranges[k].first == 1) make_leaf(child, order_[ranges[k].first]);
      else fill(child, ranges[k].first, ranges[k].second);
    }
    summarize(id, first, static_cast<std::uint8_t>(ranges.size()));
  }

  void make_leaf(std::uint32_t id, std::uint32_t i) {
    Node& n = nodes_[id];
    const Vec3f p = pts_.positions[i];
    n.center[0] = p.x, n.center[1] = p.y, n.center[2] = p.z;
    n.radius = pts_.radii[i];
    n.normal = pts_.normals[i];
    n.cone = 0;
    n.color = pts_.has_colors() ? pts_.colors[i] : Rgb8{255, 255, 255};
  }

  // Reorders order_[b, e) so the lower half of the longest axis comes first; returns the split.
  std::size_t split(std::size_t b, std::size_t e) {
    Bounds box;
    for (std::size_t i = b; i < e; ++i) box.add(pts_.positions[order_[i]]);
    const Vec3f size = box.size();
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    const float mid = 0.5f * (box.min[axis] + box.max[axis]);
    auto first = order_.begin() + static_cast<std::ptrdiff_t>(b), last = order_.begin() + static_cast<std::ptrdiff_t>(e);
    auto m = std::stable_partition(first, last, [&](std::uint32_t i) { return pts_.positions[i][axis] < mid; });
    if (m == first || m == last) m = first + (last - first) / 2;  // coincident points: split by count
    return static_cast<std::size_t>(m - order_.begin());
  }

  // Interior node values from its children (§2.5), on unquantised values: mean centre, enclosing
  // radius, normalised normal sum, cone = max(angle to child + child cone), truncated mean colour.
  void summarize(std::uint32_t id, std::uint32_t first, std::uint8_t count) {
    double c[3] = {0, 0, 0};
    Vec3f nsum{};
    unsigned rgb[3] = {0, 0, 0};
    bool grand = false;
    for (std::uint32_t k = first; k < first + count; ++k) {
      const Node& ch = nodes_[k];
      for (int a = 0; a < 3; ++a) c[a] += ch.center[a];
      nsum = nsum + ch.normal;
      rgb[0] += ch.color.r, rgb[1] += ch.color.g, rgb[2] += ch.color.b;
      grand = grand || ch.child_count > 0;
    }
    Node& m = nodes_[id];
    m.first_child = first;
    m.child_count = count;
    m.has_grandchildren = grand;
    for (int a = 0; a < 3; ++a) m.center[a] = static_cast<float>(c[a] / count);
    m.normal = normalized(nsum);
    m.color = {static_cast<std::uint8_t>(rgb[0] / count), static_cast<std::uint8_t>(rgb[1] / count),
               static_cast<std::uint8_t>(rgb[2] / count)};
    m.radius = 0, m.cone = 0;
    for (std::uint32_t k = first; k < first + count; ++k) {
      const Node& ch = nodes_[k];
      const Vec3f d{ch.center[0] - m.center[0], ch.center[1] - m.center[1], ch.center[2] - m.center[2]};
      m.radius = std::max(m.radius, length(d) + ch.radius);
      const float angle = std::acos(std::clamp(dot(m.normal, ch.normal), 0.0f, 1.0f));
      m.cone = std::max(m.cone, angle + ch.cone);
    }
  }

  const PointSet& pts_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

void put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}
void put_be_float(std::vector<std::uint8_t>& out, float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  put_be32(out, u);
}

std::size_t group_bytes(const Node& n, std::size_t node_size) {
  return (n.has_grandchildren ? 4 : 0) + node_size * n.child_count;
}

// The comment fragment (§1.4): comment lines joined with newlines, zero-padded to a multiple of 4.
void write_comment_fragment(std::vector<std::uint8_t>& out, const std::vector<std::string>& comments) {
  std::string text;
  for (const std::string& c : comments) text += c + "\n";
  const std::size_t len = (qsplat::kCommentHeaderBytes + text.size() + 3) / 4 * 4;
  out.insert(out.end(), {'Q', 'S', 'p', 'l', 'a', 't', '1', '1'});
  put_be32(out, static_cast<std::uint32_t>(len));
  put_be32(out, 0);
  put_be32(out, qsplat::kOptionComment);
  out.insert(out.end(), text.begin(), text.end());
  out.resize(out.size() + (len - qsplat::kCommentHeaderBytes - text.size()), 0);
}

// The data fragment (§7.3): header, then groups in breadth-first order of their parents, each
// child quantised against its parent's decoded sphere, which then replaces the child's own.
void write_data_fragment(std::vector<std::uint8_t>& out, std::vector<Node>& nodes, std::size_t leaves, bool colored) {
  const std::size_t node_size = colored ? 6 : 4;
  const std::size_t start = out.size();
  const Node& root = nodes[0];
  out.insert(out.end(), {'Q', 'S', 'p', 'l', 'a', 't', '1', '1'});
  put_be32(out, 0);  // fragment length, patched below
  put_be32(out, static_cast<std::uint32_t>(leaves));
  put_be32(out, colored ? qsplat::kOptionColor : 0);
  for (int a = 0; a < 3; ++a) put_be_float(out, root.center[a]);
  put_be_float(out, root.radius);
  put_be32(out, root.child_count);

  std::deque<std::uint32_t> queue;
  std::size_t queued_bytes = 0;  // on-disk size of the groups of the nodes in the queue
  if (root.child_count) {
    queue.push_back(0);
    queued_bytes = group_bytes(root, node_size);
  }
  while (!queue.empty()) {
    const std::uint32_t id = queue.front();
    queue.pop_front();
    const Node& parent = nodes[id];
    // The offset reaches past this group and every group still queued to the first child group.
    if (parent.has_grandchildren) put_be32(out, static_cast<std::uint32_t>(queued_bytes));
    queued_bytes -= group_bytes(parent, node_size);
    for (std::uint32_t k = parent.first_child; k < parent.first_child + parent.child_count; ++k) {
      Node& ch = nodes[k];
      const int s = qsplat::encode_sphere(ch.center, ch.radius, parent.center, parent.radius);
      qsplat::decode_sphere(qsplat::sphere_table()[s], parent.center, parent.radius, ch.center, ch.radius);
      const unsigned cc = ch.child_count ? ch.child_count - 1u : 0u;
      const unsigned w0 = (unsigned(s) << 3) | (ch.has_grandchildren ? 4u : 0u) | cc;
      const unsigned w1 = (unsigned(qsplat::encode_normal(ch.normal)) << 2) | unsigned(qsplat::encode_cone(ch.cone));
      out.push_back(static_cast<std::uint8_t>(w0 >> 8));
      out.push_back(static_cast<std::uint8_t>(w0));
      out.push_back(static_cast<std::uint8_t>(w1 >> 8));
      out.push_back(static_cast<std::uint8_t>(w1));
      if (colored) {
        const std::uint16_t c = qsplat::encode_color(ch.color);
        out.push_back(static_cast<std::uint8_t>(c >> 8));
        out.push_back(static_cast<std::uint8_t>(c));
      }
      if (ch.child_count) {
        queue.push_back(k);
        queued_bytes += group_bytes(ch, node_size);
      }
    }
  }
  out.resize(start + (out.size() - start + 3) / 4 * 4, 0);  // zero padding (§1.5 allows any bytes)
  const auto len = static_cast<std::uint32_t>(out.size() - start);
  for (int b = 0; b < 4; ++b) out[start + 8 + b] = static_cast<std::uint8_t>(len >> (24 - 8 * b));
}

}  // namespace

std::vector<std::uint8_t> encode_qsplat(const PointSet& points, std::vector<std::uint32_t>* leaf_order) {
  std::vector<std::uint8_t> out;
  if (!points.comments.empty()) write_comment_fragment(out, points.comments);
  TreeBuilder builder(points);
  std::vector<Node> nodes = builder.build();
  if (leaf_order) *leaf_order = builder.leaf_order();
  write_data_fragment(out, nodes, points.size(), points.has_colors());
  return out;
}

}  // namespace qf
