// PLY reader: ascii, binary_little_endian and binary_big_endian; any property types; point sets
// (vertex element only) and triangle meshes (vertex + face elements, polygons split into fans).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>

#include "core/file_io.h"
#include "io/model_io.h"
#include "io/ply_header.h"
#include "io/reader_util.h"

namespace qf {
namespace {

using io::quote_token;

using namespace ply;

// ---------------------------------------------------------------------------------------------
// Body: values land in a Sink, which knows the vertex layout and collects faces.

struct Sink {
  const std::string& path;
  io::NonFiniteFilter& nonfinite;
  // vertex attributes
  std::vector<Vec3f> positions, normals;
  std::vector<Rgb8> colors;
  std::vector<float> radii;
  bool want_normals = false, want_colors = false, want_radii = false;
  // faces (flat fans), checked against the header's vertex count as they are read
  std::uint64_t vertex_count = 0;
  std::vector<Triangle> triangles;
  std::size_t polygons_triangulated = 0;
  // Streaming (a file without faces): every block_points vertices go to `block` as a point set,
  // `first` the file index of the block's first vertex.
  const std::function<void(PointSet&)>* block = nullptr;
  std::size_t block_points = 0, first = 0;
  const std::vector<std::string>* comments = nullptr;
  ReadReport* report = nullptr;
  // A streamed file's pages before the current record (`at`, binary bodies) are released at each
  // block: a 3 GB file does not stay resident while its points go to scratch.
  const InputFile* file = nullptr;
  std::size_t at = 0;
};

// Hands the vertices read so far to the block's taker (streaming), the non-finite ones dropped.
void flush_block(Sink& s) {
  if (s.positions.empty()) return;
  const std::size_t read = s.positions.size();
  PointSet p;
  p.positions = std::move(s.positions), p.normals = std::move(s.normals);
  p.colors = std::move(s.colors), p.radii = std::move(s.radii);
  p.comments = *s.comments;
  s.nonfinite.apply(p, s.report, s.first);
  s.first += read;
  if (p.size()) (*s.block)(p);
  if (s.file) s.file->release(s.at);
  s.positions.clear(), s.normals.clear(), s.colors.clear(), s.radii.clear();
  s.positions.reserve(s.block_points);
}

// Converts a colour value of any PLY type to 8 bits (floats are taken as [0,1]).
std::uint8_t to_color8(double v, Type t) {
  if (t == Type::kUInt8) return static_cast<std::uint8_t>(v);
  double c = v;
  if (t == Type::kFloat32 || t == Type::kFloat64) c = v * 255.0;
  else if (t == Type::kUInt16) c = v / 257.0;
  if (!(c > 0)) return 0;  // also NaN
  if (c >= 255) return 255;
  return static_cast<std::uint8_t>(std::lround(c));
}

// One vertex's values, gathered before being stored.
struct VertexValues {
  double v[11] = {};  // indexed by Dest
};

template <class Where>
void store_vertex(Sink& s, const VertexValues& vv, const Type* dest_types, std::size_t index, Where&& where) {
  const Vec3f p{static_cast<float>(vv.v[int(Dest::kX)]), static_cast<float>(vv.v[int(Dest::kY)]),
                static_cast<float>(vv.v[int(Dest::kZ)])};
  s.nonfinite.check(index, p, "ply.body.nonfinite", where);
  s.positions.push_back(p);
  if (s.want_normals) {
    const Vec3f n{static_cast<float>(vv.v[int(Dest::kNX)]), static_cast<float>(vv.v[int(Dest::kNY)]),
                  static_cast<float>(vv.v[int(Dest::kNZ)])};
    s.normals.push_back(as_unit(n));
  }
  if (s.want_colors)
    s.colors.push_back({to_color8(vv.v[int(Dest::kRed)], dest_types[int(Dest::kRed)]),
                        to_color8(vv.v[int(Dest::kGreen)], dest_types[int(Dest::kGreen)]),
                        to_color8(vv.v[int(Dest::kBlue)], dest_types[int(Dest::kBlue)])});
  if (s.want_radii) {
    const double r = vv.v[int(Dest::kRadius)];
    // Checked as the float it is stored as: a double radius of 1e300 is not finite there.
    if (!(r >= 0) || !std::isfinite(r) || r > std::numeric_limits<float>::max())
      throw InputError("ply.body.bad_radius", s.path, where(),
                       "radius of vertex " + std::to_string(index) + " is " + std::to_string(r) +
                           ", expected a finite value >= 0");
    s.radii.push_back(static_cast<float>(r));
  }
  if (s.block && s.positions.size() >= s.block_points) flush_block(s);
}

constexpr long long kMaxListLength = 1 << 20;

template <class Where>
void add_face(Sink& s, const std::vector<long long>& idx, Where&& where) {
  if (idx.size() < 3)
    throw InputError("ply.body.list_length", s.path, where(),
                     "face with " + std::to_string(idx.size()) + " vertex indices, expected at least 3");
  for (long long i : idx)
    if (i < 0 || static_cast<std::uint64_t>(i) >= s.vertex_count)
      throw InputError("ply.body.face_index", s.path, where(),
                       "face vertex index " + std::to_string(i) + " out of range, expected 0.." +
                           std::to_string(static_cast<long long>(s.vertex_count) - 1) + " (the header declares " +
                           std::to_string(s.vertex_count) + " vertices)");
  if (idx.size() > 3) ++s.polygons_triangulated;
  for (std::size_t k = 1; k + 1 < idx.size(); ++k)
    s.triangles.push_back({static_cast<std::uint32_t>(idx[0]), static_cast<std::uint32_t>(idx[k]),
                           static_cast<std::uint32_t>(idx[k + 1])});
}

// -- binary ------------------------------------------------------------------------------------

template <class T>
T load(const std::uint8_t* p, bool swap) {
  T v;
  std::memcpy(&v, p, sizeof v);
  if (swap) {
    std::uint8_t b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    std::reverse(b, b + sizeof v);
    std::memcpy(&v, b, sizeof v);
  }
  return v;
}

double load_value(const std::uint8_t* p, Type t, bool swap) {
  switch (t) {
    case Type::kInt8: return static_cast<std::int8_t>(*p);
    case Type::kUInt8: return *p;
    case Type::kInt16: return load<std::int16_t>(p, swap);
    case Type::kUInt16: return load<std::uint16_t>(p, swap);
    case Type::kInt32: return load<std::int32_t>(p, swap);
    case Type::kUInt32: return load<std::uint32_t>(p, swap);
    case Type::kFloat32: return load<float>(p, swap);
    case Type::kFloat64: return load<double>(p, swap);
  }
  return 0;
}

template <class T>
void decode_column_as(const std::uint8_t* p, std::size_t stride, std::size_t n, bool swap, double* out) {
  if (swap) {
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<double>(load<T>(p + i * stride, true));
  } else {
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<double>(load<T>(p + i * stride, false));
  }
}

// Reads one property of n records `stride` bytes apart into out[0..n).
void decode_column(const std::uint8_t* p, std::size_t stride, std::size_t n, Type t, bool swap, double* out) {
  switch (t) {
    case Type::kInt8: return decode_column_as<std::int8_t>(p, stride, n, swap, out);
    case Type::kUInt8: return decode_column_as<std::uint8_t>(p, stride, n, swap, out);
    case Type::kInt16: return decode_column_as<std::int16_t>(p, stride, n, swap, out);
    case Type::kUInt16: return decode_column_as<std::uint16_t>(p, stride, n, swap, out);
    case Type::kInt32: return decode_column_as<std::int32_t>(p, stride, n, swap, out);
    case Type::kUInt32: return decode_column_as<std::uint32_t>(p, stride, n, swap, out);
    case Type::kFloat32: return decode_column_as<float>(p, stride, n, swap, out);
    case Type::kFloat64: return decode_column_as<double>(p, stride, n, swap, out);
  }
}

class BinaryBody {
 public:
  BinaryBody(ByteView bytes, std::size_t offset, bool swap, const std::string& path)
      : data_(bytes.data()), pos_(offset), end_(bytes.size()), swap_(swap), path_(path) {}

  void read_element(const Element& e, bool is_vertex, bool is_face, Sink& s, const Type* dest_types) {
    const bool fixed = std::none_of(e.props.begin(), e.props.end(), [](const Property& p) { return p.is_list; });
    if (fixed) read_fixed(e, is_vertex, s, dest_types);
    else read_with_lists(e, is_vertex, is_face, s, dest_types);
  }

  std::size_t position() const { return pos_; }

 private:
  // Fixed-size records: check the whole element fits once, then decode without bounds checks.
  void read_fixed(const Element& e, bool is_vertex, Sink& s, const Type* dest_types) {
    std::size_t stride = 0;
    for (const Property& p : e.props) stride += type_size(p.type);
    const std::size_t available = end_ - pos_;
    if (stride != 0 && e.count > available / stride)
      throw InputError("ply.body.truncated", path_, at_byte(pos_),
                       "file ends inside element '" + e.name + "': " + std::to_string(e.count) + " records of " +
                           std::to_string(stride) + " bytes need " + std::to_string(e.count * stride) +
                           " bytes, only " + std::to_string(available) + " remain (file size " +
                           std::to_string(end_) + ")");
    if (!is_vertex) {
      pos_ += static_cast<std::size_t>(e.count) * stride;
      return;
    }
    // Decode a block of records column by column: the type switch stays outside the inner
    // loops, which keeps the reader near memory speed (foundation issue: >= 300 MB/s).
    constexpr std::size_t kBlock = 512;
    std::vector<double> columns(11 * kBlock);
    for (std::uint64_t b0 = 0; b0 < e.count; b0 += kBlock) {
      const std::size_t m = static_cast<std::size_t>(std::min<std::uint64_t>(kBlock, e.count - b0));
      const std::uint8_t* base = data_ + pos_ + static_cast<std::size_t>(b0) * stride;
      std::size_t offset = 0;
      for (const Property& p : e.props) {
        if (p.dest != Dest::kSkip) decode_column(base + offset, stride, m, p.type, swap_, &columns[int(p.dest) * kBlock]);
        offset += type_size(p.type);
      }
      for (std::size_t j = 0; j < m; ++j) {
        VertexValues vv;
        for (const Property& p : e.props)
          if (p.dest != Dest::kSkip) vv.v[int(p.dest)] = columns[int(p.dest) * kBlock + j];
        const std::size_t record = pos_ + static_cast<std::size_t>(b0 + j) * stride;
        s.at = record;
        store_vertex(s, vv, dest_types, static_cast<std::size_t>(b0 + j), [&] { return at_byte(record); });
      }
    }
    pos_ += static_cast<std::size_t>(e.count) * stride;
  }

  // Records with lists: walk value by value.
  void read_with_lists(const Element& e, bool is_vertex, bool is_face, Sink& s, const Type* dest_types) {
    std::vector<long long> indices;
    for (std::uint64_t i = 0; i < e.count; ++i) {
      const std::size_t record = pos_;
      VertexValues vv;
      for (const Property& p : e.props) {
        if (!p.is_list) {
          const double v = read_checked(p.type, e, i);
          if (is_vertex && p.dest != Dest::kSkip) vv.v[int(p.dest)] = v;
          continue;
        }
        const std::size_t count_at = pos_;
        const double c = read_checked(p.count_type, e, i);
        if (c < 0 || c > kMaxListLength)
          throw InputError("ply.body.list_length", path_, at_byte(count_at),
                           "list '" + p.name + "' of " + e.name + " " + std::to_string(i) + " has length " +
                               std::to_string(static_cast<long long>(c)) + ", expected 0.." +
                               std::to_string(kMaxListLength));
        const auto n = static_cast<std::size_t>(c);
        const std::size_t bytes = n * type_size(p.type);
        if (bytes > end_ - pos_)
          throw InputError("ply.body.truncated", path_, at_byte(count_at),
                           "list '" + p.name + "' of " + e.name + " " + std::to_string(i) + " needs " +
                               std::to_string(bytes) + " bytes, only " + std::to_string(end_ - pos_) + " remain");
        if (is_face && p.is_face_indices) {
          indices.resize(n);
          for (std::size_t k = 0; k < n; ++k) {
            const double v = load_value(data_ + pos_ + k * type_size(p.type), p.type, swap_);
            if (v != std::floor(v))
              throw InputError("ply.body.face_index", path_, at_byte(pos_), "face index " + std::to_string(v) + " is not an integer");
            indices[k] = static_cast<long long>(v);
          }
        }
        pos_ += bytes;
      }
      if (is_vertex) store_vertex(s, vv, dest_types, i, [&] { return at_byte(record); });
      if (is_face) add_face(s, indices, [&] { return at_byte(record); });
    }
  }

  double read_checked(Type t, const Element& e, std::uint64_t i) {
    if (type_size(t) > end_ - pos_)
      throw InputError("ply.body.truncated", path_, at_byte(end_),
                       "file ends inside " + e.name + " " + std::to_string(i) + " of " + std::to_string(e.count));
    const double v = load_value(data_ + pos_, t, swap_);
    pos_ += type_size(t);
    return v;
  }

  const std::uint8_t* data_;
  std::size_t pos_, end_;
  bool swap_;
  const std::string& path_;
};

// -- ascii -------------------------------------------------------------------------------------

class AsciiBody {
 public:
  AsciiBody(ByteView bytes, const Header& h, const std::string& path)
      : tok_(reinterpret_cast<const char*>(bytes.data()) + h.body_offset,
             reinterpret_cast<const char*>(bytes.data()) + bytes.size(), h.body_line),
        path_(path) {}

  void read_element(const Element& e, bool is_vertex, bool is_face, Sink& s, const Type* dest_types) {
    // Records without properties hold no text: skip the element at once, whatever its count (a
    // count of 2^63 must not loop), as the binary reader does.
    if (e.props.empty()) return;
    std::vector<long long> indices;
    for (std::uint64_t i = 0; i < e.count; ++i) {
      VertexValues vv;
      std::size_t line = 0;
      for (const Property& p : e.props) {
        const std::string_view t = next(e, i);
        if (line == 0) line = tok_.line();
        if (!p.is_list) {
          const double v = number(t, p.type, e, p);
          if (is_vertex && p.dest != Dest::kSkip) vv.v[int(p.dest)] = v;
          continue;
        }
        const double c = number(t, p.count_type, e, p);
        if (c < 0 || c > kMaxListLength)
          throw InputError("ply.body.list_length", path_, at_line(tok_.line()),
                           "list '" + p.name + "' has length " + std::string(t) + ", expected 0.." +
                               std::to_string(kMaxListLength));
        const auto n = static_cast<std::size_t>(c);
        if (is_face && p.is_face_indices) indices.resize(n);
        for (std::size_t k = 0; k < n; ++k) {
          const double v = number(next(e, i), p.type, e, p);
          if (is_face && p.is_face_indices) indices[k] = static_cast<long long>(v);
        }
      }
      if (is_vertex) store_vertex(s, vv, dest_types, i, [&] { return at_line(line); });
      if (is_face) add_face(s, indices, [&] { return at_line(line); });
    }
  }

  void expect_end() {
    if (!tok_.at_end())
      throw InputError("ply.body.trailing", path_, at_line(tok_.line()),
                       "unexpected data " + quote_token(tok_.next()) + " after the last element");
  }

 private:
  std::string_view next(const Element& e, std::uint64_t i) {
    const std::string_view t = tok_.next();
    if (t.empty())
      throw InputError("ply.body.truncated", path_, at_line(tok_.line()),
                       "file ends inside " + e.name + " " + std::to_string(i) + " of " + std::to_string(e.count));
    return t;
  }
  // Parses a value of the declared type. Values outside the type's range are an error (a binary
  // file cannot hold them either): "uchar 300" or an int index of 2^63-1 is not silently cast.
  double number(std::string_view t, Type type, const Element& e, const Property& p) {
    if (is_integer_type(type)) {
      long long v;
      if (!io::parse_int64(t, v)) {
        const bool digits = !t.empty() && t.find_first_not_of("+-0123456789") == std::string_view::npos;
        throw InputError(digits ? "ply.body.out_of_range" : "ply.body.bad_number", path_, at_line(tok_.line()),
                         (digits ? "value " + quote_token(t) + " of " + e.name + " property '" + p.name +
                                       "' is out of range for " + type_name(type) + " (" + type_range(type) + ")"
                                 : "expected an integer for " + e.name + " property '" + p.name + "', found " +
                                       quote_token(t)));
      }
      if (v < integer_min(type) || v > integer_max(type))
        throw InputError("ply.body.out_of_range", path_, at_line(tok_.line()),
                         "value " + std::to_string(v) + " of " + e.name + " property '" + p.name +
                             "' is out of range for " + type_name(type) + " (" + type_range(type) + ")");
      return static_cast<double>(v);
    }
    double v;
    if (!io::parse_double(t, v)) {
      // from_chars rejects "nan"/"inf" spellings with signs in some forms; accept the usual ones.
      if (t == "nan" || t == "-nan" || t == "NaN" || t == "inf" || t == "-inf" || t == "Inf" || t == "-Inf")
        return t[0] == '-' ? -INFINITY : (t.back() == 'n' || t.back() == 'N' ? NAN : INFINITY);
      // from_chars reports result_out_of_range for finite spellings beyond double (1e999).
      double ignored;
      const bool too_big = !t.empty() && std::from_chars(t.data() + (t[0] == '+'), t.data() + t.size(), ignored).ec ==
                                             std::errc::result_out_of_range;
      throw InputError(too_big ? "ply.body.out_of_range" : "ply.body.bad_number", path_, at_line(tok_.line()),
                       too_big ? "value " + quote_token(t) + " of " + e.name + " property '" + p.name +
                                     "' is out of range for " + type_name(type)
                               : "expected a number for " + e.name + " property '" + p.name + "', found " + quote_token(t));
    }
    if (type == Type::kFloat32 && std::isfinite(v) && std::fabs(v) > std::numeric_limits<float>::max())
      throw InputError("ply.body.out_of_range", path_, at_line(tok_.line()),
                       "value " + quote_token(t) + " of " + e.name + " property '" + p.name +
                           "' is out of range for float (magnitude up to 3.4e38)");
    return v;
  }

  io::Tokenizer tok_;
  const std::string& path_;
};

}  // namespace

// ---------------------------------------------------------------------------------------------

Model read_ply(const std::string& path, const ReadOptions& options, ReadReport* report) {
  const InputFile file(path);
  return decode_ply(file.bytes(), path, options, report);
}

namespace {

// What the body is read into: the vertex and face elements (face null when it carries no
// indices) and, per vertex destination, whether a property lands there and its type.
struct BodyLayout {
  Element* vertex = nullptr;
  Element* face = nullptr;
  Type dest_types[11] = {};
  bool seen[11] = {};
};

// Step 1: finds the vertex and face elements and maps their properties.
BodyLayout map_elements(Header& h, const std::string& path) {
  BodyLayout l;
  for (Element& e : h.elements) {
    if (e.name == "vertex" && !l.vertex) l.vertex = &e;
    if (e.name == "face" && !l.face) l.face = &e;
  }
  if (!l.vertex) throw InputError("ply.header.no_vertex", path, "", "no 'element vertex' in the header");
  for (Property& p : l.vertex->props) {
    p.dest = vertex_dest(p.name);
    if (p.dest == Dest::kSkip) continue;
    if (p.is_list)
      throw InputError("ply.header.property_type", path, at_line(l.vertex->header_line),
                       "vertex property '" + p.name + "' is a list, expected a scalar");
    l.seen[int(p.dest)] = true;
    l.dest_types[int(p.dest)] = p.type;
  }
  if (!l.seen[int(Dest::kX)] || !l.seen[int(Dest::kY)] || !l.seen[int(Dest::kZ)])
    throw InputError("ply.header.no_xyz", path, at_line(l.vertex->header_line),
                     "vertex element lacks one of the properties x, y, z");
  if (l.face) {
    for (Property& p : l.face->props)
      if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        if (!is_integer_type(p.type))
          throw InputError("ply.header.property_type", path, at_line(l.face->header_line),
                           "face list '" + p.name + "' has non-integer type, expected an integer type");
        p.is_face_indices = true;
        break;
      }
    if (std::none_of(l.face->props.begin(), l.face->props.end(), [](const Property& p) { return p.is_face_indices; }))
      l.face = nullptr;  // a face element without indices carries nothing we use
  }
  return l;
}

// Step 2: every element in file order (unknown ones are walked over), ascii or binary.
void read_body(ByteView bytes, const Header& h, const BodyLayout& l, Sink& sink, const std::string& path) {
  if (h.format == Format::kAscii) {
    AsciiBody body(bytes, h, path);
    for (const Element& e : h.elements) body.read_element(e, &e == l.vertex, &e == l.face, sink, l.dest_types);
    body.expect_end();
    return;
  }
  const bool little_host = [] {
    const std::uint16_t one = 1;
    std::uint8_t b;
    std::memcpy(&b, &one, 1);
    return b == 1;
  }();
  const bool swap = (h.format == Format::kBinaryLE) != little_host;
  BinaryBody body(bytes, h.body_offset, swap, path);
  for (const Element& e : h.elements) body.read_element(e, &e == l.vertex, &e == l.face, sink, l.dest_types);
  if (body.position() != bytes.size())
    throw InputError("ply.body.trailing", path, at_byte(body.position()),
                     std::to_string(bytes.size() - body.position()) +
                         " bytes after the last element; the header's counts do not match the body");
}

// Step 3: what was read, as a mesh (when there are faces) or a point set.
Model to_model(Sink& sink, Header& h, bool mesh, io::NonFiniteFilter& nonfinite, ReadReport* report) {
  Model m;
  if (mesh) {
    m.is_mesh = true;
    m.mesh.positions = std::move(sink.positions);
    m.mesh.normals = std::move(sink.normals);
    m.mesh.colors = std::move(sink.colors);
    m.mesh.triangles = std::move(sink.triangles);
    m.mesh.comments = std::move(h.comments);
    nonfinite.apply(m.mesh, report);
  } else {
    m.points.positions = std::move(sink.positions);
    m.points.normals = std::move(sink.normals);
    m.points.colors = std::move(sink.colors);
    m.points.radii = std::move(sink.radii);
    m.points.comments = std::move(h.comments);
    nonfinite.apply(m.points, report);
  }
  return m;
}

}  // namespace

namespace {

// Steps 1-2 of decode_ply: the header, then the body into `sink` (made here, handed to `done`
// with the header and whether the file holds faces).
template <class Done>
auto decode_ply_into(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report,
                     const std::function<void(PointSet&)>* block, std::size_t block_points, const InputFile* file, Done&& done) {
  if (bytes.empty()) throw InputError("ply.header.magic", path, "", "file is empty, expected a PLY header");
  Header h = parse_header(bytes, path);
  const BodyLayout l = map_elements(h, path);
  if (block && l.face) throw UsageError(path + ": a PLY file with faces (a mesh) is not read as a stream of points");
  io::NonFiniteFilter nonfinite(path, options);
  Sink sink{path, nonfinite, {}, {}, {}, {}, false, false, false, l.vertex->count, {}, 0};
  sink.want_normals = l.seen[int(Dest::kNX)] && l.seen[int(Dest::kNY)] && l.seen[int(Dest::kNZ)];
  sink.want_colors = l.seen[int(Dest::kRed)] && l.seen[int(Dest::kGreen)] && l.seen[int(Dest::kBlue)];
  sink.want_radii = l.seen[int(Dest::kRadius)];
  sink.block = block, sink.block_points = std::max<std::size_t>(1, block_points);
  sink.comments = &h.comments, sink.report = report, sink.file = file;
  const std::size_t reserve = block ? std::min<std::size_t>(sink.block_points, l.vertex->count)
                                    : static_cast<std::size_t>(std::min<std::uint64_t>(l.vertex->count, bytes.size()));
  sink.positions.reserve(reserve);
  if (sink.want_normals) sink.normals.reserve(reserve);
  if (sink.want_colors) sink.colors.reserve(reserve);
  if (sink.want_radii) sink.radii.reserve(reserve);
  read_body(bytes, h, l, sink, path);
  if (report) {
    report->format = h.format == Format::kAscii       ? "ply (ascii)"
                     : h.format == Format::kBinaryLE ? "ply (binary_little_endian)"
                                                      : "ply (binary_big_endian)";
    report->polygons_triangulated += sink.polygons_triangulated;
  }
  return done(sink, h, l.face != nullptr, nonfinite);
}

}  // namespace

Model decode_ply(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report) {
  return decode_ply_into(bytes, path, options, report, nullptr, 0, nullptr,
                         [&](Sink& sink, Header& h, bool mesh, io::NonFiniteFilter& nonfinite) {
                           return to_model(sink, h, mesh, nonfinite, report);
                         });
}

std::optional<std::uint64_t> ply_point_count(const std::string& path) {
  const InputFile file(path);
  if (file.bytes().empty()) return std::nullopt;
  try {
    Header h = parse_header(file.bytes(), path);
    const BodyLayout l = map_elements(h, path);
    if (l.face) return std::nullopt;
    return l.vertex->count;
  } catch (const InputError&) {
    return std::nullopt;  // read whole, which says what is wrong
  }
}

void stream_ply(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report,
                std::size_t block_points, const std::function<void(PointSet&)>& block, const InputFile* file) {
  decode_ply_into(bytes, path, options, report, &block, block_points, file, [](Sink& sink, Header&, bool, io::NonFiniteFilter&) {
    flush_block(sink);
    return 0;
  });
}

}  // namespace qf
