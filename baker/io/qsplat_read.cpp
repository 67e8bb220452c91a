// QSplat .qs reader: every leaf of every data fragment becomes a point (position, normal, radius,
// colour); comment fragments become PointSet::comments. Layout: shared/specs/qsplat-format.md §1, §2, §7.2.
#include <cmath>
#include <cstring>

#include "core/file_io.h"
#include "io/model_io.h"
#include "io/qsplat_codec.h"
#include "io/reader_util.h"

namespace qf {
namespace {

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}
float be_float(const std::uint8_t* p) {
  const std::uint32_t u = be32(p);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// A sibling group being walked: its records are read one by one; an interior record's child group
// is walked before the next sibling, so leaves come out in depth-first (tree) order, which is the
// order the writer's spatial partition put them in.
struct Group {
  std::size_t rec;         // file offset of the next record to read
  int left;                // records still to read
  std::size_t next_child;  // file offset of the next child group (parents with grandchildren only)
  bool has_offset;         // the group started with a child offset (parent has grandchildren)
  float center[3];         // parent's decoded sphere
  float radius;
};

class FragmentDecoder {
 public:
  FragmentDecoder(ByteView bytes, std::size_t start, std::size_t end, const std::string& path,
                  PointSet& out, bool colored)
      : d_(bytes.data()), start_(start), end_(end), path_(path), out_(out), colored_(colored) {}

  // Decodes the tree of the data fragment at start_ and returns the number of leaves found.
  std::size_t decode(std::int32_t header_leaves) {
    const std::uint8_t* h = d_ + start_;
    float root_center[3] = {be_float(h + 20), be_float(h + 24), be_float(h + 28)};
    const float root_radius = be_float(h + 32);
    const std::int32_t k0 = static_cast<std::int32_t>(be32(h + 36));
    if (!std::isfinite(root_center[0]) || !std::isfinite(root_center[1]) || !std::isfinite(root_center[2]) ||
        !std::isfinite(root_radius) || root_radius < 0)
      fail("qsplat.root", start_ + 20, "root sphere is not finite or has a negative radius");
    if (k0 < 0 || k0 > 4) fail("qsplat.root", start_ + 36, "root child count " + std::to_string(k0) + ", expected 0..4");
    if (k0 == 0) {
      // §2.4: a single point is stored as the root itself; its normal and colour are not stored.
      if (header_leaves != 1) return 0;
      out_.positions.push_back({root_center[0], root_center[1], root_center[2]});
      out_.radii.push_back(root_radius);
      out_.normals.push_back({0, 0, 1});
      out_.colors.push_back({255, 255, 255});
      return 1;
    }
    const std::size_t node_size = colored_ ? 6 : 4;
    // §2.4: the first group has an offset iff the fragment has more leaves than root children.
    open_group(start_ + qsplat::kHeaderBytes, k0, header_leaves > k0, root_center, root_radius, node_size);
    std::size_t leaves = 0, interior = 0;
    while (!stack_.empty()) {
      Group& g = stack_.back();
      if (g.left == 0) {
        stack_.pop_back();
        continue;
      }
      read_record(g, header_leaves, node_size, leaves, interior);  // may reallocate stack_: g is not used after
    }
    return leaves;
  }

 private:
  // The next record of group g: a leaf becomes a point; an interior node opens its children's
  // group. Counts both against the header's leaves.
  void read_record(Group& g, std::int32_t header_leaves, std::size_t node_size, std::size_t& leaves, std::size_t& interior) {
    const auto& spheres = qsplat::sphere_table();
    const auto& normals = qsplat::normal_table();
    const std::size_t rec = g.rec;
    g.rec += node_size;
    --g.left;
    const std::uint8_t* p = d_ + rec;
    const unsigned w0 = (unsigned(p[0]) << 8) | p[1];
    const unsigned w1 = (unsigned(p[2]) << 8) | p[3];
    const unsigned sphere = w0 >> 3, cc = w0 & 3, grand = (w0 >> 2) & 1;
    if (sphere >= static_cast<unsigned>(qsplat::kSphereEntries))
      fail("qsplat.sphere_index", rec, "sphere index " + std::to_string(sphere) + " is invalid, expected 0.." +
                                           std::to_string(qsplat::kSphereEntries - 1));
    float c[3], r;
    qsplat::decode_sphere(spheres[sphere], g.center, g.radius, c, r);
    if (cc == 0) {
      if (grand) fail("qsplat.node", rec, "leaf record with the has-grandchildren flag set");
      out_.positions.push_back({c[0], c[1], c[2]});
      out_.radii.push_back(r);
      out_.normals.push_back(normals[w1 >> 2]);
      // Uncoloured fragments get white (QSplat's default); the caller drops colours if no fragment had any.
      out_.colors.push_back(colored_ ? qsplat::decode_color(static_cast<std::uint16_t>((p[4] << 8) | p[5]))
                                     : Rgb8{255, 255, 255});
      if (++leaves > static_cast<std::size_t>(header_leaves))
        fail("qsplat.leaf_count", rec, "tree holds more leaves than the header's " + std::to_string(header_leaves));
      return;
    }
    if (!g.has_offset)
      fail("qsplat.node", rec, "interior record in a group whose parent was marked as having no grandchildren");
    // Every interior node has at least two children, so there are fewer interior nodes than
    // leaves; this also bounds the work on a file whose offsets make groups overlap.
    if (++interior > static_cast<std::size_t>(header_leaves))
      fail("qsplat.leaf_count", rec, "tree holds more interior nodes than the header's " + std::to_string(header_leaves) + " leaves allow");
    const int count = static_cast<int>(cc) + 1;
    const std::size_t child = g.next_child;
    g.next_child += (grand ? 4 : 0) + node_size * static_cast<std::size_t>(count);
    open_group(child, count, grand != 0, c, r, node_size);  // may reallocate stack_: g is not used after
  }

  // Checks a group's bytes and pushes it; its child offset (if any) must point forward into the fragment.
  void open_group(std::size_t at, int count, bool has_offset, const float center[3], float radius, std::size_t node_size) {
    Group g{at, count, 0, has_offset, {center[0], center[1], center[2]}, radius};
    if (has_offset) {
      need(at, 4, "child offset");
      const std::int32_t off = static_cast<std::int32_t>(be32(d_ + at));
      // Groups are written breadth first, so a child group always lies after its parent's group.
      const std::size_t min_target = at + 4 + node_size * static_cast<std::size_t>(count);
      if (off <= 0 || at + static_cast<std::size_t>(off) < min_target || at + static_cast<std::size_t>(off) >= end_)
        fail("qsplat.child_offset", at,
             "child offset " + std::to_string(off) + " points outside the fragment or back into the tree (fragment ends at byte " +
                 std::to_string(end_) + ")");
      g.next_child = at + static_cast<std::size_t>(off);
      g.rec = at + 4;
    }
    need(g.rec, node_size * static_cast<std::size_t>(count), "node records");
    stack_.push_back(g);
  }

  void need(std::size_t at, std::size_t n, const char* what) {
    if (at > end_ || n > end_ - at)
      fail("qsplat.truncated", at, std::string(what) + " run past the end of the fragment (fragment ends at byte " +
                                        std::to_string(end_) + ")");
  }
  [[noreturn]] void fail(const char* code, std::size_t at, const std::string& what) {
    throw InputError(code, path_, at_byte(at), what);
  }

  const std::uint8_t* d_;
  std::size_t start_, end_;
  const std::string& path_;
  PointSet& out_;
  bool colored_;
  std::vector<Group> stack_;
};

// A comment fragment's text, one comment per line (zero padding dropped, §1.4).
void read_comment(const std::uint8_t* h, std::int32_t len, PointSet& out) {
  std::string text(reinterpret_cast<const char*>(h + 20), static_cast<std::size_t>(len - 20));
  while (!text.empty() && text.back() == '\0') text.pop_back();  // zero padding (§1.4)
  std::size_t a = 0;
  while (a < text.size()) {
    std::size_t b = text.find('\n', a);
    if (b == std::string::npos) b = text.size();
    out.comments.push_back(text.substr(a, b - a));
    a = b + 1;
  }
}

// A data fragment (its header checked: length, leaves, options) decoded into `out`; returns 1,
// the fragments it counts.
std::size_t read_data_fragment(ByteView bytes, std::size_t pos, std::int32_t len, std::int32_t leaves, std::uint32_t options,
                               const std::string& path, PointSet& out, bool& any_color) {
  if (len < qsplat::kHeaderBytes)
    throw InputError("qsplat.fragment_length", path, at_byte(pos + 8), "data fragment shorter than its 40-byte header");
  if (leaves < 0) throw InputError("qsplat.leaf_count", path, at_byte(pos + 12), "negative leaf count " + std::to_string(leaves));
  const bool colored = (options & qsplat::kOptionColor) != 0;
  any_color = any_color || colored;
  const std::size_t node_size = colored ? 6 : 4;
  // Each leaf needs its own record, so the header cannot claim more leaves than records fit.
  if (static_cast<std::size_t>(leaves) > (static_cast<std::size_t>(len) - qsplat::kHeaderBytes) / node_size + 1)
    throw InputError("qsplat.leaf_count", path, at_byte(pos + 12),
                     "header claims " + std::to_string(leaves) + " leaves, more than the fragment's " +
                         std::to_string(len) + " bytes can hold");
  FragmentDecoder dec(bytes, pos, pos + static_cast<std::size_t>(len), path, out, colored);
  const std::size_t found = dec.decode(leaves);
  if (found != static_cast<std::size_t>(leaves))
    throw InputError("qsplat.leaf_count", path, at_byte(pos + 12),
                     "header says " + std::to_string(leaves) + " leaves, the tree holds " + std::to_string(found));
  return 1;
}

}  // namespace

PointSet read_qsplat(const std::string& path, const ReadOptions& /*options*/, ReadReport* report) {
  // Decoded positions are always finite (finite root, bounded table), so ReadOptions has nothing to drop.
  const InputFile file(path);
  return decode_qsplat(file.bytes(), path, report);
}

PointSet decode_qsplat(ByteView bytes, const std::string& path, ReadReport* report) {
  PointSet out;
  std::size_t pos = 0, fragments = 0;
  bool any_color = false;
  if (bytes.empty()) throw InputError("qsplat.magic", path, at_byte(0), "file is empty, expected 'QSplat11'");
  while (pos < bytes.size()) {
    const std::size_t left = bytes.size() - pos;
    if (left < 8 || std::memcmp(bytes.data() + pos, "QSplat", 6) != 0)
      throw InputError("qsplat.magic", path, at_byte(pos), "expected the fragment magic 'QSplat11'");
    if (bytes[pos + 6] != '1' || bytes[pos + 7] != '1')
      throw InputError("qsplat.version", path, at_byte(pos + 6),
                       "version " + io::quote_token({reinterpret_cast<const char*>(bytes.data() + pos + 6), 2}) +
                           ", expected '11' (QSplat 1.0)");
    if (left < static_cast<std::size_t>(qsplat::kCommentHeaderBytes))
      throw InputError("qsplat.truncated", path, at_byte(pos), "fragment header cut short");
    const std::uint8_t* h = bytes.data() + pos;
    const std::int32_t len = static_cast<std::int32_t>(be32(h + 8));
    const std::int32_t leaves = static_cast<std::int32_t>(be32(h + 12));
    const std::uint32_t options = be32(h + 16);
    const bool comment = (options & qsplat::kOptionComment) != 0;
    const std::int32_t min_len = comment ? qsplat::kCommentHeaderBytes : qsplat::kHeaderBytes;
    if (len < min_len || len % 4 != 0 || static_cast<std::size_t>(len) > left) {
      // §1.3: a header written little-endian by a broken 64-bit build is recognisable.
      const std::uint32_t le = std::uint32_t(h[8]) | (std::uint32_t(h[9]) << 8) | (std::uint32_t(h[10]) << 16) |
                               (std::uint32_t(h[11]) << 24);
      const std::string hint = (le >= std::uint32_t(min_len) && le <= left && le % 4 == 0)
                                   ? " (the field reads as a plausible little-endian length: the file was written by a "
                                     "64-bit build of qsplat_make that did not byte-swap, and is not a valid QSplat file)"
                                   : "";
      throw InputError("qsplat.fragment_length", path, at_byte(pos + 8),
                       "fragment length " + std::to_string(len) + ", expected a multiple of 4 between " +
                           std::to_string(min_len) + " and the " + std::to_string(left) + " bytes left" + hint);
    }
    if (options & ~(qsplat::kOptionColor | qsplat::kOptionComment))
      throw InputError("qsplat.options", path, at_byte(pos + 16), "unknown option bits " + std::to_string(options) + ", expected 0..3");
    if (comment) read_comment(h, len, out);
    else fragments += read_data_fragment(bytes, pos, len, leaves, options, path, out, any_color);
    pos += static_cast<std::size_t>(len);
  }
  if (!any_color) out.colors.clear();
  if (report) {
    report->format = "qsplat";
    report->fragments += fragments;
  }
  return out;
}

}  // namespace qf
