// Writers: binary little-endian PLY (points or meshes, every attribute present) and XYZ/PWN text.
// All outputs go through write_file_atomically.
#include <charconv>
#include <cstring>
#include <ostream>

#include "core/error.h"
#include "core/file_io.h"
#include "io/model_io.h"

namespace qf {
namespace {

// Appends the raw little-endian bytes of a value (the host is little-endian: x86-64, aarch64).
template <class T>
void put(std::string& buf, T v) {
  static_assert(std::is_trivially_copyable_v<T>);
  char b[sizeof v];
  std::memcpy(b, &v, sizeof v);
  buf.append(b, sizeof v);
}

void write_comments(std::ostream& out, const std::vector<std::string>& comments) {
  for (const std::string& c : comments) {
    // A comment line cannot hold a newline; split multi-line comments.
    std::size_t a = 0;
    while (a <= c.size()) {
      std::size_t b = c.find('\n', a);
      if (b == std::string::npos) b = c.size();
      out << "comment " << c.substr(a, b - a) << "\n";
      a = b + 1;
    }
  }
}

void write_vertex_header(std::ostream& out, std::size_t n, bool normals, bool colors, bool radii,
                         const std::vector<ScalarField>& scalars) {
  out << "element vertex " << n << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals) out << "property float nx\nproperty float ny\nproperty float nz\n";
  if (colors) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (radii) out << "property float radius\n";
  for (const ScalarField& s : scalars) out << "property float " << s.name << "\n";
}

// Writes the vertex records in chunks so memory stays bounded for big sets.
template <class Record>
void write_records(std::ostream& out, std::size_t n, Record&& record) {
  std::string buf;
  constexpr std::size_t kChunk = 1 << 16;
  for (std::size_t i = 0; i < n; ++i) {
    record(buf, i);
    if (buf.size() >= kChunk) {
      out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
      buf.clear();
    }
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
}

// Shortest text that reads back to the same float (deterministic across runs and platforms).
void put_text(std::string& buf, float v) {
  char tmp[32];
  const auto r = std::to_chars(tmp, tmp + sizeof tmp, v == 0.0f ? 0.0f : v);  // no "-0"
  buf.append(tmp, r.ptr);
}

}  // namespace

void write_ply(const std::string& path, const PointSet& p) {
  for (const ScalarField& s : p.scalars)
    if (s.values.size() != p.size()) throw std::logic_error("write_ply: scalar field '" + s.name + "' has the wrong size");
  write_file_atomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\n";
    write_comments(out, p.comments);
    write_vertex_header(out, p.size(), p.has_normals(), p.has_colors(), p.has_radii(), p.scalars);
    out << "end_header\n";
    write_records(out, p.size(), [&](std::string& b, std::size_t i) {
      put(b, p.positions[i]);
      if (p.has_normals()) put(b, p.normals[i]);
      if (p.has_colors()) put(b, p.colors[i]);
      if (p.has_radii()) put(b, p.radii[i]);
      for (const ScalarField& s : p.scalars) put(b, s.values[i]);
    });
  });
}

void write_ply(const std::string& path, const TriangleMesh& m) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\n";
    write_comments(out, m.comments);
    write_vertex_header(out, m.positions.size(), !m.normals.empty(), !m.colors.empty(), false, {});
    out << "element face " << m.triangles.size() << "\nproperty list uchar uint vertex_indices\nend_header\n";
    write_records(out, m.positions.size(), [&](std::string& b, std::size_t i) {
      put(b, m.positions[i]);
      if (!m.normals.empty()) put(b, m.normals[i]);
      if (!m.colors.empty()) put(b, m.colors[i]);
    });
    write_records(out, m.triangles.size(), [&](std::string& b, std::size_t i) {
      put(b, std::uint8_t{3});
      put(b, m.triangles[i]);
    });
  });
}

void write_xyz(const std::string& path, const PointSet& p, bool require_normals) {
  if (require_normals && !p.has_normals())
    throw InputError("convert.needs_normals", path, "", "a .pwn file needs normals and this point set has none");
  write_file_atomically(path, [&](std::ostream& out) {
    write_records(out, p.size(), [&](std::string& b, std::size_t i) {
      const Vec3f v = p.positions[i];
      put_text(b, v.x), b += ' ', put_text(b, v.y), b += ' ', put_text(b, v.z);
      if (p.has_normals()) {
        const Vec3f n = p.normals[i];
        b += ' ', put_text(b, n.x), b += ' ', put_text(b, n.y), b += ' ', put_text(b, n.z);
      }
      b += '\n';
    });
  });
}

}  // namespace qf
