// Building blocks the generated assets share (parts.h).
#include "shapes/parts.h"

#include <cmath>

namespace qf::shape_parts {
namespace {

// A leaf: a pointed oval (u across, v along from the stalk at v = 1 to the tip at v = 0) with a
// lighter midrib; alpha 0 outside it, so a MASK material cuts the quad to the leaf's shape. The
// cut-away texels keep a leaf green (as texture artists dilate colour into them): black there
// would bleed into the leaf's edge in an engine's mipmaps and darken the tree at a distance.
TextureImage leaf_texture() {
  TextureImage t{64, 64, std::vector<std::uint8_t>(64 * 64 * 4, 0)};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double u = (x + 0.5) / 32.0 - 1, v = (y + 0.5) / 64.0;      // u in -1..1, v in 0..1
      const double half_width = 0.95 * std::sin(kPi * v) * std::sqrt(v);  // widest past the middle
      if (std::fabs(u) > half_width) {
        std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * 64 + x) * 4];
        p[0] = 50, p[1] = 110, p[2] = 34, p[3] = 0;
        continue;
      }
      const double rib = std::fabs(u) < 0.06 ? 1.25 : 1.0;
      const double shade = (0.7 + 0.3 * (1 - std::fabs(u) / std::max(half_width, 1e-6))) * rib;
      std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * 64 + x) * 4];
      p[0] = static_cast<std::uint8_t>(std::min(255.0, 60 * shade)), p[1] = static_cast<std::uint8_t>(std::min(255.0, 130 * shade));
      p[2] = static_cast<std::uint8_t>(std::min(255.0, 40 * shade)), p[3] = 255;
    }
  return t;
}

}  // namespace

// Bark: brown with vertical grooves and a little noise, repeating around the trunk.
TextureImage bark_texture(SplitMix64& random) {
  TextureImage t{64, 64, std::vector<std::uint8_t>(64 * 64 * 4)};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double groove = 0.75 + 0.25 * std::sin(x * 2 * kPi / 8.0 + 0.8 * std::sin(y * 2 * kPi / 32.0));
      const double shade = groove * (0.85 + 0.15 * random.uniform());
      std::uint8_t* p = &t.rgba[static_cast<std::size_t>(y * 64 + x) * 4];
      p[0] = static_cast<std::uint8_t>(110 * shade), p[1] = static_cast<std::uint8_t>(78 * shade);
      p[2] = static_cast<std::uint8_t>(50 * shade), p[3] = 255;
    }
  return t;
}

// Any two unit vectors perpendicular to unit d and to each other.
void frame(Vec3f d, Vec3f& a, Vec3f& b) {
  a = normalized(cross(d, std::fabs(d.y) < 0.9f ? Vec3f{0, 1, 0} : Vec3f{1, 0, 0}));
  b = cross(d, a);
}

// A unit direction uniform on the sphere (parts.h).
Direction random_direction(SplitMix64& random) {
  const double z = 2 * random.uniform() - 1, phi = 2 * kPi * random.uniform();
  return {std::sqrt(1 - z * z) * std::cos(phi), z, std::sqrt(1 - z * z) * std::sin(phi)};
}

// A point uniform in a ball of `radius` about the origin (a direction, then the distance), its
// height scaled by `squash` and raised by `lift`: where a plant's leaves gather about a tip.
Vec3f random_in_ball(SplitMix64& random, double radius, double squash, double lift) {
  const Direction d = random_direction(random);
  const double r = radius * std::cbrt(random.uniform());
  return vec(d.x * r, d.y * r * squash + lift, d.z * r);
}

// A tapered tube from `from` along unit `dir`, `length` long, radius r0 -> r1, with the bark's
// texture coordinates (u around, twice; v along, one repeat per unit).
void add_tube(TriangleMesh& mesh, Vec3f from, Vec3f dir, double length, double r0, double r1, int kSides, int kRings) {
  Vec3f a, b;
  frame(dir, a, b);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (int i = 0; i <= kRings; ++i) {
    const double f = static_cast<double>(i) / kRings, r = r0 + (r1 - r0) * f;
    for (int k = 0; k < kSides; ++k) {
      const double angle = 2 * kPi * k / kSides;
      const Vec3f radial = a * static_cast<float>(std::cos(angle)) + b * static_cast<float>(std::sin(angle));
      mesh.positions.push_back(from + dir * static_cast<float>(length * f) + radial * static_cast<float>(r));
      mesh.normals.push_back(radial);
    }
  }
  for (int i = 0; i < kRings; ++i)
    for (int k = 0; k < kSides; ++k) {
      const auto v = [&](int ring, int side) { return base + static_cast<std::uint32_t>(ring * kSides + (side % kSides)); };
      const float u0 = 2.0f * static_cast<float>(k) / kSides, u1 = 2.0f * static_cast<float>(k + 1) / kSides;
      const float v0 = static_cast<float>(length * i / kRings), v1 = static_cast<float>(length * (i + 1) / kRings);
      mesh.triangles.push_back({v(i, k), v(i, k + 1), v(i + 1, k + 1)});
      mesh.corner_uvs.push_back({Vec2f{u0, v0}, Vec2f{u1, v0}, Vec2f{u1, v1}});
      mesh.triangles.push_back({v(i, k), v(i + 1, k + 1), v(i + 1, k)});
      mesh.corner_uvs.push_back({Vec2f{u0, v0}, Vec2f{u1, v1}, Vec2f{u0, v1}});
      mesh.triangle_materials.insert(mesh.triangle_materials.end(), 2, 0u);
    }
}

// A beam of square section `width` from a to b: a box of 8 corners and 12 triangles, wound
// counter-clockwise seen from outside.
void add_beam(TriangleMesh& mesh, Vec3f a, Vec3f b, float width) {
  const Vec3f d = normalized(b - a);
  const Vec3f u = normalized(cross(d, std::fabs(d.y) < 0.9f ? Vec3f{0, 1, 0} : Vec3f{1, 0, 0})) * (0.5f * width);
  const Vec3f v = normalized(cross(d, u)) * (0.5f * width);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (const Vec3f& end : {a, b})
    for (const Vec3f& c : {u + v, v - u, (u + v) * -1.0f, u - v}) mesh.positions.push_back(end + c);
  // Sides k: corners k, k+1 at a (0..3) and at b (4..7); then the two end caps.
  for (std::uint32_t k = 0; k < 4; ++k) {
    const std::uint32_t k1 = (k + 1) % 4;
    mesh.triangles.push_back({base + k, base + k1, base + 4 + k1});
    mesh.triangles.push_back({base + k, base + 4 + k1, base + 4 + k});
  }
  mesh.triangles.push_back({base + 0, base + 2, base + 1});
  mesh.triangles.push_back({base + 0, base + 3, base + 2});
  mesh.triangles.push_back({base + 4, base + 5, base + 6});
  mesh.triangles.push_back({base + 4, base + 6, base + 7});
}

// A leaf quad at `at` facing unit `n`, its stalk end pointing along `along` (in the leaf's plane).
void add_leaf(TriangleMesh& mesh, Vec3f at, Vec3f n, Vec3f along, float length, float width) {
  const Vec3f across = normalized(cross(n, along));
  const Vec3f up = cross(across, n);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  const Vec3f corners[4] = {at - across * (0.5f * width), at + across * (0.5f * width),
                            at + across * (0.5f * width) + up * length, at - across * (0.5f * width) + up * length};
  for (const Vec3f& c : corners) mesh.positions.push_back(c), mesh.normals.push_back(n);
  // Texture v = 1 at the stalk (the quad's base), 0 at the tip. Wound counter-clockwise seen from
  // the side `n` points to (across x up = -n, so the corners go 0 3 2 1): engines take the winding
  // for the front, and flip a double-sided back face's normal; a winding against NORMAL would
  // leave every leaf lit from behind, ambient only.
  mesh.triangles.push_back({base, base + 3, base + 2});
  mesh.corner_uvs.push_back({Vec2f{0, 1}, Vec2f{0, 0}, Vec2f{1, 0}});
  mesh.triangles.push_back({base, base + 2, base + 1});
  mesh.corner_uvs.push_back({Vec2f{0, 1}, Vec2f{1, 0}, Vec2f{1, 1}});
  mesh.triangle_materials.insert(mesh.triangle_materials.end(), 2, 1u);
}

SurfaceMaterial card_material(const std::string& name, int texture) {
  SurfaceMaterial m;
  m.name = name;
  m.texture = texture;
  m.wrap_s = m.wrap_t = TextureWrap::kClampToEdge;
  m.alpha_mode = AlphaMode::kMask;
  m.double_sided = true;
  return m;
}

// Bark (repeating) and leaves (cut out by alpha, seen from both sides): materials 0 and 1.
void add_plant_materials(TriangleMesh& mesh, SplitMix64& random) {
  mesh.textures = {bark_texture(random), leaf_texture()};
  SurfaceMaterial bark;
  bark.name = "bark";
  bark.texture = 0;
  mesh.materials = {bark, card_material("leaf", 1)};
}

}  // namespace qf::shape_parts
