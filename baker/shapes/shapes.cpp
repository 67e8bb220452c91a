// Analytic sample shapes: octahedron (paper fig. 1), cube with a checker pattern, sphere, torus,
// two planes meeting at a right-angled crease, and a scan-like scene.
#include "shapes/shapes.h"

#include <algorithm>
#include <cmath>

#include "analysis/neighborhoods.h"
#include "core/error.h"
#include "core/random.h"

namespace qf {
namespace {

using Random = SplitMix64;

constexpr double kPi = 3.14159265358979323846;

void add(PointSet& p, Vec3f pos, Vec3f normal, Rgb8 color) {
  p.positions.push_back(pos);
  p.normals.push_back(normalized(normal));
  p.colors.push_back(color);
}

// Points spread over `parts` equal-area parts: part k gets its share of n (the first n % parts get one more).
std::size_t share(std::size_t n, std::size_t parts, std::size_t k) { return n / parts + (k < n % parts ? 1 : 0); }

Vec3f in_triangle(Random& r, Vec3f a, Vec3f b, Vec3f c) {
  double u = r.uniform(), v = r.uniform();
  if (u + v > 1) u = 1 - u, v = 1 - v;  // fold the unit square onto the triangle: uniform by area
  return a + (b - a) * static_cast<float>(u) + (c - a) * static_cast<float>(v);
}

PointSet octahedron(const ShapeOptions& o) {
  // One saturated colour per face, as in the paper's figure 1a.
  static const Rgb8 kFace[8] = {{230, 25, 75}, {60, 180, 75}, {255, 225, 25}, {0, 130, 200},
                                {245, 130, 48}, {145, 30, 180}, {70, 240, 240}, {240, 50, 230}};
  Random r(o.seed);
  PointSet p;
  for (std::size_t f = 0; f < 8; ++f) {
    const float sx = (f & 1) ? -1.f : 1.f, sy = (f & 2) ? -1.f : 1.f, sz = (f & 4) ? -1.f : 1.f;
    const Vec3f a{sx, 0, 0}, b{0, sy, 0}, c{0, 0, sz};
    for (std::size_t i = 0; i < share(o.points, 8, f); ++i) add(p, in_triangle(r, a, b, c), {sx, sy, sz}, kFace[f]);
  }
  return p;
}

PointSet cube(const ShapeOptions& o) {
  // Each face of [-1,1]^3 is a 4x4 checkerboard of its own colour and white.
  static const Rgb8 kFace[6] = {{200, 40, 40}, {40, 160, 60}, {40, 80, 200}, {220, 180, 30}, {150, 50, 170}, {30, 170, 170}};
  Random r(o.seed);
  PointSet p;
  for (std::size_t f = 0; f < 6; ++f) {
    const int axis = static_cast<int>(f / 2);
    const float side = (f & 1) ? -1.f : 1.f;
    for (std::size_t i = 0; i < share(o.points, 6, f); ++i) {
      const float u = static_cast<float>(2 * r.uniform() - 1), v = static_cast<float>(2 * r.uniform() - 1);
      Vec3f pos, n;
      pos[axis] = side, pos[(axis + 1) % 3] = u, pos[(axis + 2) % 3] = v;
      n[axis] = side;
      const int cu = static_cast<int>(std::floor((u + 1) * 2)), cv = static_cast<int>(std::floor((v + 1) * 2));
      add(p, pos, n, ((cu + cv) & 1) ? Rgb8{245, 245, 245} : kFace[f]);
    }
  }
  return p;
}

PointSet sphere(const ShapeOptions& o) {
  // Unit sphere; z uniform in [-1,1] and longitude uniform is uniform by area (Archimedes).
  // Colour encodes the normal, so orientation is visible at a glance.
  Random r(o.seed);
  PointSet p;
  for (std::size_t i = 0; i < o.points; ++i) {
    const double z = 2 * r.uniform() - 1, phi = 2 * kPi * r.uniform(), s = std::sqrt(std::max(0.0, 1 - z * z));
    const Vec3f n{static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)), static_cast<float>(z)};
    auto c = [](float x) { return static_cast<std::uint8_t>(std::lround(127.5f * (x + 1))); };
    add(p, n, n, {c(n.x), c(n.y), c(n.z)});
  }
  return p;
}

PointSet torus(const ShapeOptions& o) {
  // Major radius 1, minor radius 0.35, axis z; 12 colour stripes around the ring.
  constexpr double R = 1.0, t = 0.35;
  Random r(o.seed);
  PointSet p;
  while (p.size() < o.points) {
    const double u = 2 * kPi * r.uniform(), v = 2 * kPi * r.uniform();
    // Area element is proportional to R + t cos v: accept with that probability (rejection sampling).
    if (r.uniform() * (R + t) > R + t * std::cos(v)) continue;
    const Vec3f n{static_cast<float>(std::cos(v) * std::cos(u)), static_cast<float>(std::cos(v) * std::sin(u)),
                  static_cast<float>(std::sin(v))};
    const Vec3f pos{static_cast<float>((R + t * std::cos(v)) * std::cos(u)),
                    static_cast<float>((R + t * std::cos(v)) * std::sin(u)), static_cast<float>(t * std::sin(v))};
    const bool stripe = static_cast<int>(std::floor(u / (2 * kPi) * 12)) % 2 == 0;
    add(p, pos, n, stripe ? Rgb8{220, 120, 40} : Rgb8{40, 90, 200});
  }
  return p;
}

PointSet crease(const ShapeOptions& o) {
  // Two unit squares meeting at a 90-degree crease along the z axis: the plane y = 0 (x in [0,1])
  // and the plane x = 0 (y in [0,1]), normals pointing into the open side.
  Random r(o.seed);
  PointSet p;
  for (std::size_t side = 0; side < 2; ++side)
    for (std::size_t i = 0; i < share(o.points, 2, side); ++i) {
      const float a = static_cast<float>(r.uniform()), z = static_cast<float>(r.uniform());
      if (side == 0) add(p, {a, 0, z}, {0, 1, 0}, {210, 60, 50});
      else add(p, {0, a, z}, {1, 0, 0}, {50, 110, 210});
    }
  return p;
}

// A single-station terrestrial scan of a small scene (Y up): a ground plane, a building with
// windows and two poles, seen from a scanner at kScanner. What makes it scan-like: density falls
// with the square of the distance and with the incidence angle (a point is kept with probability
// cos(incidence) (2 / distance)^2), surfaces facing away or hidden behind the building are not
// seen (holes, shadows), the range is noisy (0.15% of the distance, along the ray), and every
// 500th point is an outlier anywhere in the scene's box (a mixed pixel). Normals are the
// surfaces' (an outlier's faces the scanner).
PointSet scan(const ShapeOptions& o) {
  const Vec3f kScanner{0.3f, 1.7f, 4.0f};
  const Vec3f box_min{-1.2f, 0.0f, -0.8f}, box_max{1.2f, 1.4f, 0.2f};  // the building
  // Whether the segment from p to the scanner passes through the building (slab test), p being
  // nudged off its own surface first.
  const auto hidden = [&](Vec3f p, Vec3f n) {
    const Vec3f a = p + n * 1e-4f, d = kScanner - a;
    double t0 = 0, t1 = 1;
    for (int k = 0; k < 3; ++k) {
      if (std::fabs(d[k]) < 1e-12f) {
        if (a[k] < box_min[k] || a[k] > box_max[k]) return false;
        continue;
      }
      double ta = (box_min[k] - a[k]) / d[k], tb = (box_max[k] - a[k]) / d[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta), t1 = std::min(t1, tb);
      if (t0 > t1) return false;
    }
    return true;
  };
  struct Part {
    double area;
    int kind;  // 0 ground, 1..5 building faces (front, back, left, right, roof), 6..7 poles
  };
  const Part parts[] = {{5.0 * 4.5, 0}, {2.4 * 1.4, 1}, {2.4 * 1.4, 2}, {1.0 * 1.4, 3}, {1.0 * 1.4, 4}, {2.4 * 1.0, 5},
                        {2 * kPi * 0.06 * 1.8, 6}, {2 * kPi * 0.06 * 1.8, 7}};
  double total = 0;
  for (const Part& q : parts) total += q.area;
  const float pole_x[2] = {1.8f, -1.9f}, pole_z[2] = {1.2f, 0.9f};
  Random r(o.seed);
  PointSet p;
  while (p.size() < o.points) {
    if (p.size() % 500 == 499) {  // an outlier: anywhere in the scene's box
      const Vec3f x{static_cast<float>(-2.5 + 5 * r.uniform()), static_cast<float>(2.2 * r.uniform()), static_cast<float>(-2 + 4.5 * r.uniform())};
      add(p, x, kScanner - x, {128, 128, 128});
      continue;
    }
    double pick = r.uniform() * total;
    int kind = 0;
    for (const Part& q : parts) {
      kind = q.kind;
      if (pick < q.area) break;
      pick -= q.area;
    }
    const float u = static_cast<float>(r.uniform()), v = static_cast<float>(r.uniform());
    Vec3f x, n;
    Rgb8 c;
    switch (kind) {
      case 0: x = {-2.5f + 5 * u, 0, -2 + 4.5f * v}, n = {0, 1, 0}, c = {110, 120, 90}; break;
      case 1: case 2: {  // front and back walls: brick, with a 4 x 2 grid of windows
        x = {-1.2f + 2.4f * u, 1.4f * v, kind == 1 ? 0.2f : -0.8f}, n = {0, 0, kind == 1 ? 1.0f : -1.0f};
        const float wu = std::fmod(u * 4, 1.0f), wv = std::fmod(v * 2, 1.0f);
        c = wu > 0.3f && wu < 0.7f && wv > 0.35f && wv < 0.8f ? Rgb8{60, 70, 90} : Rgb8{170, 70, 55};
        break;
      }
      case 3: case 4: x = {kind == 3 ? -1.2f : 1.2f, 1.4f * v, -0.8f + u}, n = {kind == 3 ? -1.0f : 1.0f, 0, 0}, c = {150, 65, 50}; break;
      case 5: x = {-1.2f + 2.4f * u, 1.4f, -0.8f + v}, n = {0, 1, 0}, c = {70, 70, 75}; break;
      default: {
        const int k = kind - 6;
        const double a = 2 * kPi * u;
        n = {static_cast<float>(std::cos(a)), 0, static_cast<float>(std::sin(a))};
        x = Vec3f{pole_x[k], 1.8f * v, pole_z[k]} + n * 0.06f;
        c = {160, 160, 165};
      }
    }
    const Vec3f ray = kScanner - x;
    const float d = length(ray);
    const float cosine = dot(n, ray) / d;
    if (cosine <= 0 || r.uniform() > std::min(1.0f, cosine * (2.0f / d) * (2.0f / d)) || hidden(x, n)) continue;
    // Range noise: a normal deviate (Box-Muller) along the ray.
    const double g = std::sqrt(-2 * std::log(1 - r.uniform())) * std::cos(2 * kPi * r.uniform());
    add(p, x - ray * static_cast<float>(0.0015 * g), n, c);
  }
  return p;
}

// A triangle split into n x n similar ones, appended to `m` with a shared-vertex grid.
void add_subdivided(TriangleMesh& m, Vec3f a, Vec3f b, Vec3f c, int n, Rgb8 color) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  auto index = [&](int i, int j) { return base + static_cast<std::uint32_t>(i * (i + 1) / 2 + j); };  // row i has i+1 vertices
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= i; ++j) {
      const float s = static_cast<float>(i) / static_cast<float>(n), t = i ? static_cast<float>(j) / static_cast<float>(n) : 0.f;
      m.positions.push_back(a + (b - a) * (s - t) + (c - a) * t);
      m.colors.push_back(color);
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      m.triangles.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      if (j < i) m.triangles.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
}

}  // namespace

TriangleMesh generate_mesh(const std::string& name, int subdivisions) {
  if (subdivisions < 1) throw UsageError("--subdivisions must be at least 1");
  static const Rgb8 kFace[8] = {{230, 25, 75}, {60, 180, 75}, {255, 225, 25}, {0, 130, 200},
                                {245, 130, 48}, {145, 30, 180}, {70, 240, 240}, {240, 50, 230}};
  TriangleMesh m;
  if (name == "octahedron" || name == "sphere") {
    // Faces counter-clockwise seen from outside; the sphere projects the octahedron's vertices.
    for (std::size_t f = 0; f < 8; ++f) {
      const float sx = (f & 1) ? -1.f : 1.f, sy = (f & 2) ? -1.f : 1.f, sz = (f & 4) ? -1.f : 1.f;
      Vec3f a{sx, 0, 0}, b{0, sy, 0}, c{0, 0, sz};
      if (sx * sy * sz < 0) std::swap(b, c);
      add_subdivided(m, a, b, c, subdivisions, kFace[f]);
    }
    if (name == "sphere")
      for (std::size_t i = 0; i < m.positions.size(); ++i) {
        m.positions[i] = normalized(m.positions[i]);
        const Vec3f n = m.positions[i];
        m.colors[i] = {static_cast<std::uint8_t>(std::lround(127.5f + 127.5f * n.x)), static_cast<std::uint8_t>(std::lround(127.5f + 127.5f * n.y)),
                       static_cast<std::uint8_t>(std::lround(127.5f + 127.5f * n.z))};
      }
  } else if (name == "cube") {
    for (int axis = 0; axis < 3; ++axis)
      for (float side : {-1.f, 1.f}) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        Vec3f c[4];
        const float cu[4] = {-1, 1, 1, -1}, cv[4] = {-1, -1, 1, 1};
        for (int k = 0; k < 4; ++k) c[k][axis] = side, c[k][u] = cu[k], c[k][v] = cv[k];
        const Rgb8 col = kFace[static_cast<std::size_t>(2 * axis + (side > 0))];
        if (side > 0) add_subdivided(m, c[0], c[1], c[2], subdivisions, col), add_subdivided(m, c[0], c[2], c[3], subdivisions, col);
        else add_subdivided(m, c[0], c[2], c[1], subdivisions, col), add_subdivided(m, c[0], c[3], c[2], subdivisions, col);
      }
  } else {
    throw UsageError("unknown mesh shape '" + name + "'; choose one of octahedron, cube, sphere");
  }
  m.comments.push_back("quasiflat sample mesh: " + name + ", " + std::to_string(subdivisions) + " subdivisions");
  return m;
}

const std::vector<ShapeInfo>& shape_catalog() {
  static const std::vector<ShapeInfo> c{
      {"octahedron", "|x|+|y|+|z| = 1, one colour per face (the paper's figure 1; the bundled sample)"},
      {"cube", "[-1,1]^3, each face a 4x4 checkerboard of its colour and white"},
      {"sphere", "unit sphere, colour = normal"},
      {"torus", "ring radius 1, tube radius 0.35, 12 colour stripes"},
      {"crease", "two unit squares meeting at a 90-degree crease along the z axis"},
      {"scan", "a single-station scan of a building, ground and poles: density falling with\n"
               "              distance and incidence, shadows, range noise, 0.2% outliers"},
  };
  return c;
}

PointSet generate_shape(const std::string& name, const ShapeOptions& options) {
  if (options.points == 0) throw UsageError("--points must be at least 1");
  PointSet p;
  if (name == "octahedron") p = octahedron(options);
  else if (name == "cube") p = cube(options);
  else if (name == "sphere") p = sphere(options);
  else if (name == "torus") p = torus(options);
  else if (name == "crease") p = crease(options);
  else if (name == "scan") p = scan(options);
  else throw UsageError("unknown shape '" + name + "'; choose one of octahedron, cube, sphere, torus, crease, scan");
  p.comments.push_back("quasiflat sample: " + name + ", " + std::to_string(options.points) + " points, seed " +
                       std::to_string(options.seed));
  estimate_radii(p);
  if (name == "scan") {
    // An outlier's own estimate (from its far neighbours) would draw it as a blob the size of the
    // scene; a scanner's mixed pixel has the beam's footprint: the median radius.
    std::vector<float> sorted = p.radii;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    for (std::size_t i = 499; i < p.size(); i += 500) p.radii[i] = sorted[sorted.size() / 2];
  }
  return p;
}

}  // namespace qf
