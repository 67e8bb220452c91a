// The gearbox assembly (machine.h): closed prisms (boxes, cylinders, gears, hex bolts), one part per
// body, written as a node per part.
#include "shapes/machine.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/random.h"
#include "gltf/glb.h"
#include "shapes/parts.h"

namespace qf {
namespace {

using shape_parts::kPi;
using shape_parts::vec;

// A closed prism: `outline` (2D, star-shaped about its origin, either winding) swept from `from`
// along unit `axis` for `length`, its caps fans from the axis; wound counter-clockwise seen from
// outside. Outline x runs along one perpendicular of the axis, y along axis x that one.
void add_prism(TriangleMesh& mesh, std::vector<Vec2f> outline, Vec3f from, Vec3f axis, double length) {
  double area = 0;
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const Vec2f p = outline[k], q = outline[(k + 1) % outline.size()];
    area += static_cast<double>(p.x) * q.y - static_cast<double>(q.x) * p.y;
  }
  if (area < 0) std::reverse(outline.begin(), outline.end());  // counter-clockwise about the axis
  Vec3f a, b;
  shape_parts::frame(axis, a, b);
  const auto n = static_cast<std::uint32_t>(outline.size()), base = static_cast<std::uint32_t>(mesh.positions.size());
  const Vec3f top = axis * static_cast<float>(length);
  for (const Vec3f end : {Vec3f{0, 0, 0}, top})
    for (const Vec2f& p : outline) mesh.positions.push_back(from + end + a * p.x + b * p.y);
  mesh.positions.push_back(from), mesh.positions.push_back(from + top);
  const std::uint32_t c0 = base + 2 * n, c1 = c0 + 1;
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t k1 = (k + 1) % n;
    mesh.triangles.push_back({base + k, base + k1, base + n + k1});
    mesh.triangles.push_back({base + k, base + n + k1, base + n + k});
    mesh.triangles.push_back({c1, base + n + k, base + n + k1});
    mesh.triangles.push_back({c0, base + k1, base + k});
  }
}

// An axis-aligned box from lo to hi.
void add_box(TriangleMesh& mesh, Vec3f lo, Vec3f hi) {
  Vec3f a, b;
  shape_parts::frame({0, 1, 0}, a, b);
  const Vec3f centre{0.5f * (lo.x + hi.x), lo.y, 0.5f * (lo.z + hi.z)};
  std::vector<Vec2f> outline;
  for (const auto& [x, z] : {std::pair{lo.x, lo.z}, {hi.x, lo.z}, {hi.x, hi.z}, {lo.x, hi.z}}) {
    const Vec3f q = Vec3f{x, lo.y, z} - centre;
    outline.push_back({dot(q, a), dot(q, b)});
  }
  add_prism(mesh, outline, centre, {0, 1, 0}, hi.y - lo.y);
}

// A cylinder of `sides` faces, or a hex bolt head with sides = 6.
void add_cylinder(TriangleMesh& mesh, Vec3f from, Vec3f axis, double length, double radius, int sides = 20) {
  std::vector<Vec2f> outline;
  for (int k = 0; k < sides; ++k)
    outline.push_back({static_cast<float>(radius * std::cos(2 * kPi * k / sides)), static_cast<float>(radius * std::sin(2 * kPi * k / sides))});
  add_prism(mesh, outline, from, axis, length);
}

// A spur gear of `teeth` teeth at pitch radius `radius` (module 2 radius / teeth: gears of one
// module mesh at the sum of their radii), trapezoid teeth from root to tip, and a hub.
void add_gear(TriangleMesh& mesh, Vec3f from, Vec3f axis, double thickness, double radius, int teeth) {
  const double module = 2 * radius / teeth, tip = radius + module, root = radius - 1.25 * module;
  std::vector<Vec2f> outline;
  for (int t = 0; t < teeth; ++t)
    for (const auto& [f, r] : {std::pair{0.0, root}, {0.2, tip}, {0.5, tip}, {0.7, root}}) {
      const double angle = 2 * kPi * (t + f) / teeth;
      outline.push_back({static_cast<float>(r * std::cos(angle)), static_cast<float>(r * std::sin(angle))});
    }
  add_prism(mesh, outline, from, axis, thickness);
  add_cylinder(mesh, from - axis * static_cast<float>(0.5 * thickness), axis, 2 * thickness, 0.3 * radius);
}

// A part of one opaque material (CAD exports carry base colours and PBR factors, no textures).
MachinePart part(const char* name, bool inner, std::array<float, 3> rgb, float metallic, float roughness, TriangleMesh mesh) {
  SurfaceMaterial m;
  m.name = name;
  m.base_color = {rgb[0], rgb[1], rgb[2], 1};
  m.metallic = metallic, m.roughness = roughness;
  mesh.materials = {m};
  mesh.triangle_materials.assign(mesh.triangles.size(), 0);
  return {name, inner, std::move(mesh)};
}

// A wall slab lo..hi with a rectangular hole through it along axis `through` (0 x, 1 y, 2 z),
// hole_lo..hole_hi in the other two axes (its `through` components ignored): four boxes round it.
void add_wall_with_hole(TriangleMesh& mesh, Vec3f lo, Vec3f hi, int through, Vec3f hole_lo, Vec3f hole_hi) {
  const int u = through == 0 ? 1 : 0, v = through == 2 ? 1 : 2;  // the wall's in-plane axes
  const auto with = [](Vec3f p, int axis, float value) {
    (axis == 0 ? p.x : axis == 1 ? p.y : p.z) = value;
    return p;
  };
  const auto at = [](Vec3f p, int axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; };
  add_box(mesh, lo, with(hi, u, at(hole_lo, u)));                                   // before the hole along u
  add_box(mesh, with(lo, u, at(hole_hi, u)), hi);                                   // after it
  add_box(mesh, with(lo, u, at(hole_lo, u)), with(with(hi, u, at(hole_hi, u)), v, at(hole_lo, v)));  // below
  add_box(mesh, with(with(lo, u, at(hole_lo, u)), v, at(hole_hi, v)), with(hi, u, at(hole_hi, u)));  // above
}

}  // namespace

Machine generate_machine(const MachineOptions& options) {
  SplitMix64 random(options.seed);
  Machine machine;
  // 1. The layout: housing box, cavity, the gear pair (one module, so they mesh), the shafts'
  //    heights (the big gear low, the small one above it), window and port.
  const Vec3f outer_lo{-0.8f, 0.1f, -0.5f}, outer_hi{0.8f, 1.15f, 0.5f};
  constexpr float kWall = 0.04f;
  const Vec3f lo = outer_lo + Vec3f{kWall, kWall, kWall}, hi = outer_hi - Vec3f{kWall, kWall, kWall};
  machine.cavity.add(lo), machine.cavity.add(hi);
  const double module = 0.012;
  const int small_teeth = 16 + static_cast<int>(random.next() % 7);
  const int big_teeth = static_cast<int>(std::lround(small_teeth * (1.6 + 0.4 * random.uniform())));
  const double r_small = 0.5 * module * small_teeth, r_big = 0.5 * module * big_teeth;
  const double y1 = lo.y + r_big + module + 0.04, y2 = y1 + r_small + r_big;
  const double gear_x = 0.05 + 0.3 * random.uniform();
  const double window_w = 0.4 + 0.15 * random.uniform(), window_h = 0.25 + 0.1 * random.uniform();
  // The window looks onto the gears' mesh, as an inspection window does.
  const double window_x = gear_x - (0.4 + 0.3 * random.uniform()) * window_w, window_y = y2 - r_small - (0.5 + 0.3 * random.uniform()) * window_h;
  // 2. Outside: the base plate and the housing (closed walls, a window in front, a port at x+).
  TriangleMesh base, housing;
  add_box(base, {-0.95f, 0, -0.62f}, {0.95f, 0.1f, 0.62f});
  add_box(housing, outer_lo, {outer_hi.x, lo.y, outer_hi.z});  // floor
  add_box(housing, {outer_lo.x, hi.y, outer_lo.z}, outer_hi);  // cover
  add_box(housing, {outer_lo.x, lo.y, outer_lo.z}, {outer_hi.x, hi.y, lo.z});  // back
  add_wall_with_hole(housing, {outer_lo.x, lo.y, hi.z}, {outer_hi.x, hi.y, outer_hi.z}, 2, vec(window_x, window_y, 0),
                     vec(window_x + window_w, window_y + window_h, 0));  // front
  add_box(housing, {outer_lo.x, lo.y, lo.z}, {lo.x, hi.y, hi.z});  // left end
  add_wall_with_hole(housing, {hi.x, lo.y, lo.z}, {outer_hi.x, hi.y, hi.z}, 0, vec(0, y2 - 0.09, -0.09), vec(0, y2 + 0.09, 0.09));  // right end
  // 3. Inside: the motor, the input shaft from it with the big gear, the output shaft with the
  //    small gear leaving through the port, bearing blocks on the end walls.
  TriangleMesh motor, input_shaft, output_shaft, big_gear, small_gear, bearings;
  add_box(motor, {lo.x, lo.y, -0.2f}, vec(-0.42, y1 + 0.13, 0.2));
  add_cylinder(input_shaft, vec(-0.45, y1, 0), {1, 0, 0}, 1.2, 0.025);
  add_cylinder(output_shaft, vec(-0.7, y2, 0), {1, 0, 0}, 1.68, 0.03);
  add_gear(big_gear, vec(gear_x - 0.03, y1, 0), {1, 0, 0}, 0.06, r_big, big_teeth);
  add_gear(small_gear, vec(gear_x - 0.03, y2, 0), {1, 0, 0}, 0.06, r_small, small_teeth);
  add_box(bearings, vec(hi.x - 0.08, y1 - 0.07, -0.07), vec(hi.x, y1 + 0.07, 0.07));
  add_box(bearings, vec(lo.x, y2 - 0.07, -0.07), vec(lo.x + 0.08, y2 + 0.07, 0.07));
  // 4. Outside again: the coupling on the output shaft, bolts along the cover's edges and at the
  //    window's corners, and a pipe run: up from the cover, along it, out past the back, down to the base.
  TriangleMesh coupling, bolts, pipe;
  add_cylinder(coupling, vec(0.88, y2, 0), {1, 0, 0}, 0.08, 0.08, 24);
  const int per_edge = 6 + static_cast<int>(random.next() % 3);
  for (int k = 0; k < per_edge; ++k)
    for (float z : {-0.44f, 0.44f}) add_cylinder(bolts, vec(-0.7 + 1.4 * k / (per_edge - 1), outer_hi.y, z), {0, 1, 0}, 0.02, 0.018, 6);
  for (double x : {window_x - 0.05, window_x + window_w + 0.05})
    for (double y : {window_y - 0.05, window_y + window_h + 0.05}) add_cylinder(bolts, vec(x, y, outer_hi.z), {0, 0, 1}, 0.02, 0.018, 6);
  const double pipe_x = 0.3 + 0.3 * random.uniform(), pipe_y = 1.28 + 0.1 * random.uniform(), r = 0.035;
  add_cylinder(pipe, vec(pipe_x, outer_hi.y - 0.02, -0.25), {0, 1, 0}, pipe_y - outer_hi.y + 0.02 + r, r);
  add_cylinder(pipe, vec(pipe_x, outer_hi.y, -0.25), {0, 1, 0}, 0.02, 0.055);  // its flange
  add_cylinder(pipe, vec(pipe_x + r, pipe_y, -0.25), {-1, 0, 0}, pipe_x + 0.6 + 2 * r, r);
  add_cylinder(pipe, vec(-0.6, pipe_y, -0.25 + r), {0, 0, -1}, 0.32 + 2 * r, r);
  add_cylinder(pipe, vec(-0.6, pipe_y + r, -0.57), {0, -1, 0}, pipe_y + r - 0.1, r);
  add_cylinder(pipe, vec(-0.6, 0.1, -0.57), {0, 1, 0}, 0.02, 0.055);
  // 5. The parts, each with its own colour, as a CAD tool exports them.
  machine.parts.push_back(part("base", false, {0.2f, 0.2f, 0.21f}, 0, 0.8f, std::move(base)));
  machine.parts.push_back(part("housing", false, {0.13f, 0.3f, 0.52f}, 0, 0.5f, std::move(housing)));
  machine.parts.push_back(part("motor", true, {0.55f, 0.08f, 0.06f}, 0, 0.5f, std::move(motor)));
  machine.parts.push_back(part("input_shaft", true, {0.6f, 0.6f, 0.62f}, 1, 0.3f, std::move(input_shaft)));
  machine.parts.push_back(part("output_shaft", false, {0.6f, 0.6f, 0.62f}, 1, 0.3f, std::move(output_shaft)));
  machine.parts.push_back(part("gear_large", true, {0.78f, 0.6f, 0.25f}, 1, 0.35f, std::move(big_gear)));
  machine.parts.push_back(part("gear_small", true, {0.78f, 0.6f, 0.25f}, 1, 0.35f, std::move(small_gear)));
  machine.parts.push_back(part("bearings", true, {0.45f, 0.42f, 0.35f}, 0, 0.6f, std::move(bearings)));
  machine.parts.push_back(part("coupling", false, {0.3f, 0.3f, 0.32f}, 1, 0.4f, std::move(coupling)));
  machine.parts.push_back(part("bolts", false, {0.25f, 0.25f, 0.27f}, 1, 0.4f, std::move(bolts)));
  machine.parts.push_back(part("pipe", false, {0.72f, 0.45f, 0.2f}, 1, 0.35f, std::move(pipe)));
  return machine;
}

std::vector<std::uint8_t> encode_machine_glb(const Machine& machine) {
  std::vector<std::vector<std::uint8_t>> files;
  std::vector<std::string> names;
  for (const MachinePart& p : machine.parts) files.push_back(encode_textured_mesh_glb(p.mesh)), names.push_back(p.name);
  std::vector<const std::vector<std::uint8_t>*> parts;
  for (const auto& f : files) parts.push_back(&f);
  return join_glb(parts, "machine", names);
}

}  // namespace qf
