// Text formats: XYZ / PWN point sets ("x y z [nx ny nz]" per line, as in CGAL's data set),
// OFF meshes (OFF, COFF, NOFF, NCOFF, CNOFF) and OBJ meshes (v, vn, f in every index form).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/file_io.h"
#include "io/model_io.h"
#include "io/asset_files.h"
#include "io/mtl_read.h"
#include "io/reader_util.h"

namespace qf {
namespace {

using io::quote_token;

// An empty file holds no model (and an empty view has no data pointer to search); a NUL byte
// means it is not a text file at all. `format` is the code prefix: "off", "obj" or "xyz".
void check_text(ByteView bytes, const std::string& path, const std::string& format, const char* expected) {
  if (bytes.empty()) throw InputError(format + ".empty", path, "", std::string("file is empty, expected ") + expected);
  const void* nul = std::memchr(bytes.data(), 0, bytes.size());
  if (nul)
    throw InputError(format + ".binary", path,
                     at_byte(static_cast<std::size_t>(static_cast<const std::uint8_t*>(nul) - bytes.data())),
                     "binary data (a NUL byte) in a text file");
}

const char* text_begin(ByteView b) { return reinterpret_cast<const char*>(b.data()); }
const char* text_end(ByteView b) { return text_begin(b) + b.size(); }

float number(std::string_view t, const std::string& path, std::size_t line, const char* code, const char* what) {
  float v;
  if (io::parse_float(t, v)) return v;
  if (t == "nan" || t == "NaN" || t == "-nan") return NAN;
  if (t == "inf" || t == "Inf") return INFINITY;
  if (t == "-inf" || t == "-Inf") return -INFINITY;
  throw InputError(code, path, at_line(line), std::string("expected a number for ") + what + ", found " +
                                                  (t.empty() ? std::string("the end of the line") : quote_token(t)));
}

// Converts a colour component: integers 0..255 as they are, values in [0,1] with a decimal point as fractions.
std::uint8_t color_component(std::string_view t, float v) {
  const bool fraction = t.find('.') != std::string_view::npos && v <= 1.0f;
  const float c = fraction ? v * 255.0f : v;
  if (!(c > 0)) return 0;
  return c >= 255 ? 255 : static_cast<std::uint8_t>(std::lround(c));
}

}  // namespace

PointSet read_xyz(const std::string& path, bool require_normals, const ReadOptions& options, ReadReport* report) {
  const InputFile file(path);
  return decode_xyz(file.bytes(), path, require_normals, options, report);
}

PointSet decode_xyz(ByteView bytes, const std::string& path, bool require_normals, const ReadOptions& options, ReadReport* report) {
  check_text(bytes, path, "xyz", "lines 'x y z [nx ny nz]'");
  io::Tokenizer tok(text_begin(bytes), text_end(bytes));
  io::NonFiniteFilter nonfinite(path, options);
  PointSet out;
  int columns = 0;  // 3 or 6, fixed by the first data line
  while (!tok.at_end()) {
    const std::size_t line = tok.line();
    std::string_view t = tok.next_on_line();
    if (t[0] == '#') {
      tok.skip_line();
      continue;
    }
    float v[6];
    int n = 0;
    for (; !t.empty(); t = tok.next_on_line()) {
      if (n == 6)
        throw InputError("xyz.columns", path, at_line(line), "more than 6 values on a line, expected 'x y z [nx ny nz]'");
      v[n++] = number(t, path, line, "xyz.bad_number", "a coordinate");
    }
    if (n != 3 && n != 6)
      throw InputError("xyz.columns", path, at_line(line),
                       std::to_string(n) + " values on a line, expected 3 (x y z) or 6 (x y z nx ny nz)");
    if (columns == 0) columns = n;
    if (n != columns)
      throw InputError("xyz.columns", path, at_line(line),
                       std::to_string(n) + " values, but earlier lines have " + std::to_string(columns));
    if (require_normals && n != 6)
      throw InputError("xyz.columns", path, at_line(line), "a .pwn line needs 6 values (x y z nx ny nz)");
    const Vec3f p{v[0], v[1], v[2]};
    nonfinite.check(out.positions.size(), p, "xyz.nonfinite", [&] { return at_line(line); });
    out.positions.push_back(p);
    if (n == 6) out.normals.push_back(as_unit({v[3], v[4], v[5]}));
  }
  if (out.positions.empty())
    throw InputError("xyz.no_points", path, at_line(tok.line()),
                     "no points in the file (only comments or blank lines), expected lines 'x y z [nx ny nz]'");
  nonfinite.apply(out, report);
  if (report) report->format = require_normals ? "pwn" : "xyz";
  return out;
}

TriangleMesh read_off(const std::string& path, const ReadOptions& options, ReadReport* report) {
  const InputFile file(path);
  return decode_off(file.bytes(), path, options, report);
}

namespace {

// decode_off's state and steps, in the order of the file: header(), counts(), vertices(), faces(),
// then finish() to make the mesh.
class OffReader {
 public:
  OffReader(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report)
      : tok_(text_begin(bytes), text_end(bytes)), path_(path), nonfinite_(path, options), report_(report), file_size_(bytes.size()) {}

  // 1. Header keyword: [C][N][4]OFF or OFF with the prefixes in either order (COFF, NOFF, NCOFF, CNOFF).
  void header() {
    key_ = next();
    const std::size_t off_at = key_.rfind("OFF");
    if (off_at == std::string_view::npos || off_at + 3 != key_.size())
      throw InputError("off.header", path_, at_line(tok_.line()), "expected 'OFF' (or COFF/NOFF/NCOFF) on the first line, found " + quote_token(key_));
    prefix_ = key_.substr(0, off_at);
    for (char c : prefix_) {
      if (c == 'C') has_color_ = true;
      else if (c == 'N') has_normal_ = true;
      else
        throw InputError("off.header", path_, at_line(tok_.line()), "unsupported OFF variant " + quote_token(key_) + ", expected OFF, COFF, NOFF or NCOFF");
    }
  }

  // 2. Counts.
  void counts() {
    long long given[3];
    for (long long& c : given) {
      const std::string_view t = next();
      if (!io::parse_int64(t, c) || c < 0)
        throw InputError("off.counts", path_, at_line(tok_.line()),
                         "expected the counts 'vertices faces edges' (integers >= 0), found " +
                             (t.empty() ? std::string("the end of the file") : quote_token(t)));
    }
    nv_ = static_cast<std::size_t>(given[0]), nf_ = static_cast<std::size_t>(given[1]);
    if (nv_ > file_size_ || nf_ > file_size_)
      throw InputError("off.counts", path_, at_line(tok_.line()), "counts larger than the file could hold");
  }

  // 3. Vertices: x y z [nx ny nz] [r g b [a]] — colour and alpha are read line-wise.
  void vertices() {
    mesh_.positions.reserve(nv_);
    for (std::size_t i = 0; i < nv_; ++i) {
      float c[3];
      std::string_view t0 = need("vertex", i, nv_);
      const std::size_t line = tok_.line();
      c[0] = number(t0, path_, line, "off.bad_number", "a vertex coordinate");
      for (int k = 1; k < 3; ++k) c[k] = number(tok_.next_on_line(), path_, line, "off.bad_number", "a vertex coordinate");
      const Vec3f p{c[0], c[1], c[2]};
      nonfinite_.check(i, p, "off.nonfinite", [&] { return at_line(line); });
      mesh_.positions.push_back(p);
      if (has_normal_) {
        float n[3];
        for (float& x : n) x = number(tok_.next_on_line(), path_, line, "off.bad_number", "a vertex normal");
        mesh_.normals.push_back(as_unit({n[0], n[1], n[2]}));
      }
      if (has_color_) {
        std::uint8_t rgb[3];
        for (auto& x : rgb) {
          const std::string_view t = tok_.next_on_line();
          x = color_component(t, number(t, path_, line, "off.bad_number", "a vertex colour"));
        }
        mesh_.colors.push_back({rgb[0], rgb[1], rgb[2]});
      }
      tok_.skip_line();  // alpha and anything else on the line
    }
  }

  // 4. Faces: n i0 .. i(n-1) [colour], polygons split into fans.
  void faces() {
    mesh_.triangles.reserve(nf_);
    std::vector<long long> idx;
    for (std::size_t f = 0; f < nf_; ++f) {
      const std::string_view t = need("face", f, nf_);
      const std::size_t line = tok_.line();
      long long n;
      if (!io::parse_int64(t, n) || n < 3 || n > (1 << 20))
        throw InputError("off.face", path_, at_line(line), "face corner count " + quote_token(t) + ", expected an integer >= 3");
      idx.resize(static_cast<std::size_t>(n));
      for (long long& i : idx) {
        const std::string_view ti = tok_.next_on_line();
        if (!io::parse_int64(ti, i))
          throw InputError("off.face", path_, at_line(line),
                           "expected " + std::to_string(n) + " vertex indices, found " +
                               (ti.empty() ? std::string("the end of the line") : quote_token(ti)));
        if (i < 0 || static_cast<std::size_t>(i) >= nv_)
          throw InputError("off.face_index", path_, at_line(line),
                           "vertex index " + std::to_string(i) + " out of range, expected 0.." + std::to_string(nv_ - 1));
      }
      tok_.skip_line();  // optional face colour
      if (n > 3 && report_) ++report_->polygons_triangulated;
      for (std::size_t k = 1; k + 1 < idx.size(); ++k)
        mesh_.triangles.push_back({static_cast<std::uint32_t>(idx[0]), static_cast<std::uint32_t>(idx[k]),
                                   static_cast<std::uint32_t>(idx[k + 1])});
    }
  }

  // 5. The mesh, less the non-finite vertices when they are to be dropped.
  TriangleMesh finish() {
    nonfinite_.apply(mesh_, report_);
    if (report_) report_->format = "off" + (prefix_.empty() ? std::string() : " (" + std::string(key_) + ")");
    return std::move(mesh_);
  }

 private:
  // Comments start with '#'; they may stand anywhere a token may.
  std::string_view next() {
    std::string_view t = tok_.next();
    while (!t.empty() && t[0] == '#') {
      tok_.skip_line();
      t = tok_.next();
    }
    return t;
  }

  // The next token of element i of n (a vertex or a face), which the file must still hold.
  std::string_view need(const char* what, std::size_t i, std::size_t n) {
    const std::string_view t = next();
    if (t.empty())
      throw InputError("off.truncated", path_, at_line(tok_.line()),
                       std::string("file ends inside ") + what + " " + std::to_string(i) + " of " + std::to_string(n));
    return t;
  }

  io::Tokenizer tok_;
  const std::string& path_;
  io::NonFiniteFilter nonfinite_;
  ReadReport* report_;
  std::size_t file_size_;
  std::string_view key_, prefix_;  // the header keyword and its C/N prefix
  bool has_color_ = false, has_normal_ = false;
  std::size_t nv_ = 0, nf_ = 0;
  TriangleMesh mesh_;
};

}  // namespace

// An OFF file's mesh: per vertex its position, normal (NOFF) and colour (COFF) in file order;
// polygons split into fans. Errors name the line and what was expected.
TriangleMesh decode_off(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report) {
  check_text(bytes, path, "off", "an OFF header");
  OffReader reader(bytes, path, options, report);
  reader.header();
  reader.counts();
  reader.vertices();
  reader.faces();
  return reader.finish();
}

TriangleMesh read_obj(const std::string& path, const ReadOptions& options, ReadReport* report) {
  const InputFile file(path);
  return decode_obj(file.bytes(), path, options, report);
}

namespace {

// decode_obj's state and steps: one method per keyword, then finish() to make the mesh.
class ObjReader {
 public:
  ObjReader(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report)
      : tok_(text_begin(bytes), text_end(bytes)), path_(path), nonfinite_(path, options), report_(report) {
    library_.root = io::asset_root(path, options.asset_root);
    library_.memory_limit = options.memory_limit;
  }

  // 1. Line by line, each keyword to its step; everything else (o, g, s, l, p, comments) carries
  //    nothing we use.
  void read_lines() {
    while (!tok_.at_end()) {
      const std::size_t line = tok_.line();
      const std::string_view key = tok_.next_on_line();
      if (key == "v") vertex(line);
      else if (key == "vn") normal(line);
      else if (key == "vt") texcoord(line);
      else if (key == "mtllib" || key == "usemtl") material_line(key, line);
      else if (key == "f") face(line);
      tok_.skip_line();
    }
  }

  // 2. The mesh: per-vertex normals and colours, per-triangle materials and texture coordinates.
  TriangleMesh finish() {
    if (mesh_.positions.empty())
      throw InputError("obj.no_vertices", path_, at_line(tok_.line()), "no vertices in the file, expected 'v x y z' lines");
    if (!any_color_) mesh_.colors.clear();
    // Per-vertex normals: the normal of the first corner that names one. Used only if every vertex has one.
    if (!vn_.empty() && std::all_of(normal_of_.begin(), normal_of_.end(), [](std::int64_t n) { return n >= 0; })) {
      mesh_.normals.reserve(normal_of_.size());
      for (std::int64_t n : normal_of_) mesh_.normals.push_back(vn_[static_cast<std::size_t>(n)]);
    }
    // A default material for triangles before the first usemtl.
    if (any_material_) {
      std::uint32_t fallback = UINT32_MAX;
      for (long long m : triangle_material_) {
        if (m < 0 && fallback == UINT32_MAX) fallback = static_cast<std::uint32_t>(mesh_.materials.size()), mesh_.materials.push_back({});
        mesh_.triangle_materials.push_back(m < 0 ? fallback : static_cast<std::uint32_t>(m));
      }
    }
    if (any_vt_)
      for (const auto& t : triangle_vt_) {
        std::array<Vec2f, 3> uv{};
        for (std::size_t k = 0; k < 3; ++k)
          if (t[k] >= 0) uv[k] = vt_[static_cast<std::size_t>(t[k])];
        mesh_.corner_uvs.push_back(uv);
      }
    nonfinite_.apply(mesh_, report_);
    if (report_) report_->format = "obj";
    return std::move(mesh_);
  }

 private:
  struct Corner {
    long long v, t, n;  // vertex, texture coordinate, normal; -1 where the corner names none
  };

  // "v x y z [r g b]": "v x y z r g b" (a common extension) carries a colour in [0,1], "v x y z w" a weight.
  void vertex(std::size_t line) {
    float v[7];
    int n = 0;
    for (std::string_view t = tok_.next_on_line(); !t.empty(); t = tok_.next_on_line()) {
      if (n == 7) throw InputError("obj.vertex", path_, at_line(line), "more than 7 values after 'v'");
      v[n++] = number(t, path_, line, "obj.bad_number", "a vertex coordinate");
    }
    if (n < 3) throw InputError("obj.vertex", path_, at_line(line), "expected 'v x y z [r g b]', found " + std::to_string(n) + " values");
    const Vec3f p{v[0], v[1], v[2]};
    nonfinite_.check(mesh_.positions.size(), p, "obj.nonfinite", [&] { return at_line(line); });
    mesh_.positions.push_back(p);
    normal_of_.push_back(-1);
    Rgb8 c{255, 255, 255};
    if (n >= 6) {
      any_color_ = true;
      auto q = [](float x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); };
      c = {q(v[3]), q(v[4]), q(v[5])};
    }
    mesh_.colors.push_back(c);
  }

  void normal(std::size_t line) {
    float n[3];
    for (float& x : n) x = number(tok_.next_on_line(), path_, line, "obj.bad_number", "a normal component");
    vn_.push_back(as_unit({n[0], n[1], n[2]}));
  }

  void texcoord(std::size_t line) {
    float uv[2];
    for (float& x : uv) x = number(tok_.next_on_line(), path_, line, "obj.bad_number", "a texture coordinate");
    vt_.push_back({uv[0], 1 - uv[1]});  // OBJ's v runs up the image, glTF's (ours) down
  }

  // mtllib FILE: its materials; usemtl NAME: the material of the faces that follow. Names may
  // hold spaces (one file per word is the format; a name with spaces is far more common).
  void material_line(std::string_view key, std::size_t line) {
    std::vector<std::string_view> words;
    for (std::string_view t = tok_.next_on_line(); !t.empty(); t = tok_.next_on_line()) words.push_back(t);
    const std::string name = io::join_words(words);
    if (key == "mtllib") {
      if (!name.empty()) io::read_mtl(path_, name, line, mesh_, library_, report_);
      return;
    }
    if (!library_.by_name.count(name)) {
      library_.by_name[name] = static_cast<std::uint32_t>(mesh_.materials.size());
      mesh_.materials.push_back({});
      mesh_.materials.back().name = name;
    }
    material_ = library_.by_name[name];
    any_material_ = true;
  }

  // f with corners v, v/vt, v/vt/vn or v//vn; polygons split into fans.
  void face(std::size_t line) {
    face_.clear();
    for (std::string_view t = tok_.next_on_line(); !t.empty(); t = tok_.next_on_line()) {
      const std::size_t s1 = t.find('/');
      long long n = -1, c = -1;
      if (s1 != std::string_view::npos) {
        const std::size_t s2 = t.find('/', s1 + 1);
        const std::string_view tt = t.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
        if (!tt.empty()) c = resolve(tt, vt_.size(), line, "texture coordinate");
        if (s2 != std::string_view::npos && s2 + 1 < t.size()) n = resolve(t.substr(s2 + 1), vn_.size(), line, "normal");
      }
      face_.push_back({resolve(t.substr(0, s1), mesh_.positions.size(), line, "vertex"), c, n});
      if (c >= 0) any_vt_ = true;
    }
    if (face_.size() < 3)
      throw InputError("obj.face", path_, at_line(line), "face with " + std::to_string(face_.size()) + " corners, expected at least 3");
    for (const Corner& c : face_)
      if (c.n >= 0 && normal_of_[static_cast<std::size_t>(c.v)] < 0) normal_of_[static_cast<std::size_t>(c.v)] = c.n;
    if (face_.size() > 3 && report_) ++report_->polygons_triangulated;
    for (std::size_t k = 1; k + 1 < face_.size(); ++k) {
      mesh_.triangles.push_back({static_cast<std::uint32_t>(face_[0].v), static_cast<std::uint32_t>(face_[k].v),
                                 static_cast<std::uint32_t>(face_[k + 1].v)});
      triangle_vt_.push_back({face_[0].t, face_[k].t, face_[k + 1].t});
      triangle_material_.push_back(material_);
    }
  }

  // OBJ indices are 1-based; negative ones count back from the last element defined so far.
  long long resolve(std::string_view t, std::size_t count, std::size_t line, const char* what) const {
    long long i;
    if (!io::parse_int64(t, i) || i == 0)
      throw InputError("obj.face", path_, at_line(line), std::string("expected a ") + what + " index, found " + quote_token(t));
    const long long r = i > 0 ? i - 1 : static_cast<long long>(count) + i;
    if (r < 0 || static_cast<std::size_t>(r) >= count)
      throw InputError("obj.face_index", path_, at_line(line),
                       std::string(what) + " index " + std::to_string(i) + " out of range: " + std::to_string(count) +
                           " defined so far");
    return r;
  }

  io::Tokenizer tok_;
  const std::string& path_;
  io::NonFiniteFilter nonfinite_;
  ReadReport* report_;
  TriangleMesh mesh_;
  std::vector<Vec3f> vn_;                // the file's normals, by vn index
  std::vector<std::int64_t> normal_of_;  // per vertex: index into vn of its first corner's normal, or -1
  std::vector<Vec2f> vt_;
  std::vector<Corner> face_;
  std::vector<std::array<long long, 3>> triangle_vt_;  // per triangle, -1 where a corner names none
  std::vector<long long> triangle_material_;           // per triangle, -1 before the first usemtl
  io::MaterialLibrary library_;
  long long material_ = -1;
  bool any_color_ = false, any_vt_ = false, any_material_ = false;
};

}  // namespace

TriangleMesh decode_obj(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report) {
  check_text(bytes, path, "obj", "'v x y z' lines");
  ObjReader reader(bytes, path, options, report);
  reader.read_lines();
  return reader.finish();
}

}  // namespace qf
