// The info command: what a file holds, as text or JSON (schemas/info.schema.json).
#include <nlohmann/json.hpp>

#include <iostream>
#include <sstream>

#include "cli/commands.h"
#include "io/model_io.h"

namespace qf::cli {
namespace {

nlohmann::json vec_json(Vec3f v) {
  return nlohmann::json::array({canonical_double(v.x), canonical_double(v.y), canonical_double(v.z)});
}

std::string vec_text(Vec3f v) {
  std::ostringstream s;
  s.precision(7);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

std::string human_bytes(std::size_t b) {
  std::ostringstream s;
  s.precision(3);
  if (b >= (1u << 20)) s << double(b) / double(1u << 20) << " MiB";
  else if (b >= 1024) s << double(b) / 1024.0 << " KiB";
  else s << b << " B";
  return s.str();
}

// What info says of a file, in both of its forms.
struct InfoFacts {
  std::vector<std::string> attributes;  // in a fixed order; "position" always
  std::vector<std::string> scalars;     // per-point scalar fields by name (LAS: "classification")
  Bounds bounds;
  std::size_t count = 0, memory = 0;
  const std::vector<std::string>* comments = nullptr;
};

InfoFacts info_facts(const Model& m) {
  InfoFacts f;
  f.attributes = {"position"};
  const bool normals = m.is_mesh ? !m.mesh.normals.empty() : m.points.has_normals();
  const bool colors = m.is_mesh ? !m.mesh.colors.empty() : m.points.has_colors();
  if (normals) f.attributes.push_back("normal");
  if (colors) f.attributes.push_back("color");
  if (m.is_mesh && !m.mesh.corner_uvs.empty()) f.attributes.push_back("texcoord");
  if (!m.is_mesh && m.points.has_radii()) f.attributes.push_back("radius");
  f.bounds = m.is_mesh ? m.mesh.bounds() : m.points.bounds();
  f.count = m.is_mesh ? m.mesh.positions.size() : m.points.size();
  f.memory = m.is_mesh ? m.mesh.memory_bytes() : m.points.memory_bytes();
  f.comments = m.is_mesh ? &m.mesh.comments : &m.points.comments;
  if (!m.is_mesh)
    for (const ScalarField& s : m.points.scalars) f.scalars.push_back(s.name);
  return f;
}

// --json (schemas/info.schema.json).
void print_info_json(const std::string& path, const Model& m, const ReadReport& report, const InfoFacts& f) {
  const Bounds& b = f.bounds;
  nlohmann::json j;
  j["file"] = path;
  j["format"] = report.format;
  j["kind"] = m.is_mesh ? "mesh" : "points";
  j[m.is_mesh ? "vertices" : "points"] = f.count;
  if (m.is_mesh) j["triangles"] = m.mesh.triangles.size();
  j["attributes"] = f.attributes;
  if (!f.scalars.empty()) j["scalars"] = f.scalars;
  if (!report.header.empty()) {
    nlohmann::json h = nlohmann::json::object();
    for (const auto& [key, value] : report.header) h[key] = value;
    j["header"] = h;
  }
  if (!b.empty()) j["bounds"] = {{"min", vec_json(b.min)}, {"max", vec_json(b.max)}, {"diagonal", canonical_double(b.diagonal())}};
  j["memory_bytes"] = f.memory;
  j["comments"] = *f.comments;
  j["dropped_nonfinite"] = report.dropped_nonfinite;
  if (m.is_mesh) {
    j["dropped_triangles"] = report.dropped_triangles;
    j["polygons_triangulated"] = report.polygons_triangulated;
  }
  if (report.fragments) j["fragments"] = report.fragments;
  if (m.is_mesh) {
    j["materials"] = m.mesh.materials.size();
    j["textures"] = m.mesh.textures.size();
    j["skipped_primitives"] = report.skipped_primitives;
  }
  j["warnings"] = report.warnings;
  std::cout << j.dump(2) << "\n";
}

void print_info_text(const std::string& path, const Model& m, const ReadReport& report, const InfoFacts& f) {
  const Bounds& b = f.bounds;
  std::string attr_text;
  for (const std::string& a : f.attributes) attr_text += (attr_text.empty() ? "" : " ") + a;
  std::cout << "file:        " << path << "\n"
            << "format:      " << report.format << "\n"
            << "kind:        " << (m.is_mesh ? "triangle mesh" : "point set") << "\n";
  if (m.is_mesh)
    std::cout << "vertices:    " << f.count << "\n"
              << "triangles:   " << m.mesh.triangles.size() << "\n";
  else
    std::cout << "points:      " << f.count << "\n";
  std::cout << "attributes:  " << attr_text << "\n";
  if (!f.scalars.empty()) {
    std::cout << "scalars:    ";
    for (const std::string& name : f.scalars) std::cout << " " << name;
    std::cout << "\n";
  }
  // The format's own header facts (LAS/LAZ), as the reader found them.
  for (const auto& [key, value] : report.header) {
    const std::string label = key + ":";
    std::cout << "  " << label << std::string(label.size() < 15 ? 15 - label.size() : 1, ' ') << value << "\n";
  }
  if (!m.is_mesh && !m.points.has_radii()) std::cout << "             (radii absent: estimated from local spacing when needed)\n";
  if (!b.empty())
    std::cout << "bounds:      min " << vec_text(b.min) << "  max " << vec_text(b.max) << "\n"
              << "size:        " << vec_text(b.size()) << "  diagonal " << b.diagonal() << "\n";
  std::cout << "memory:      " << f.memory << " bytes (" << human_bytes(f.memory) << ")\n";
  if (report.fragments) std::cout << "fragments:   " << report.fragments << "\n";
  if (report.polygons_triangulated) std::cout << "polygons:    " << report.polygons_triangulated << " split into triangles\n";
  if (report.dropped_nonfinite)
    std::cout << "dropped:     " << report.dropped_nonfinite << " non-finite points"
              << (m.is_mesh ? " and " + std::to_string(report.dropped_triangles) + " triangles" : "") << "\n";
  if (m.is_mesh && !m.mesh.materials.empty()) {
    std::cout << "materials:   " << m.mesh.materials.size();
    for (const SurfaceMaterial& mat : m.mesh.materials) std::cout << " '" << mat.name << "'";
    std::cout << "\ntextures:    " << m.mesh.textures.size();
    for (const TextureImage& t : m.mesh.textures) std::cout << " " << t.width << "x" << t.height;
    std::cout << "\n";
  }
  if (report.skipped_primitives) std::cout << "skipped:     " << report.skipped_primitives << " point or line primitives\n";
  for (const std::string& w : report.warnings) std::cout << "warning:     " << w << "\n";
  for (const std::string& c : *f.comments) std::cout << "comment:     " << c << "\n";
}

}  // namespace

int run_info(const ParsedArgs& args) {
  const std::string& path = args.positional[0];
  ReadOptions ro;
  ro.drop_nonfinite = args.flag("drop-nonfinite");
  ReadReport report;
  const Model m = read_model(path, ro, &report);
  const InfoFacts f = info_facts(m);
  if (args.flag("json")) print_info_json(path, m, report, f);
  else print_info_text(path, m, report, f);
  return 0;
}

}  // namespace qf::cli
