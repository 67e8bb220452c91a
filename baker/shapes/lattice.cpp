// The lattice tower (lattice.h).
#include "shapes/lattice.h"

#include <cmath>

#include "core/random.h"
#include "shapes/parts.h"

namespace qf {

TriangleMesh generate_lattice(const LatticeOptions& options) {
  using shape_parts::add_beam;
  SplitMix64 random(options.seed);
  TriangleMesh mesh;
  // 1. The tower's proportions from the seed.
  const int storeys = 6 + static_cast<int>(random.next() % 5);
  const double height = 3.6 + 0.8 * random.uniform(), base = 1.0 + 0.6 * random.uniform();
  const double top = base * (0.33 + 0.17 * random.uniform());
  const float width = static_cast<float>(0.025 + 0.015 * random.uniform());
  const bool x_braces = random.uniform() < 0.6;
  // Storey boundaries, closer together towards the top (as real towers are).
  const auto y_of = [&](int s) { return height * (1 - std::pow(1 - double(s) / storeys, 1.3)); };
  const auto half_at = [&](double y) { return 0.5 * (base + (top - base) * y / height); };
  const auto corner = [&](int s, int c) {  // corner c (0..3, counter-clockwise) at storey boundary s
    const double y = y_of(s), h = half_at(y);
    const double sx = (c == 0 || c == 3) ? -h : h, sz = (c < 2) ? -h : h;
    return Vec3f{static_cast<float>(sx), static_cast<float>(y), static_cast<float>(sz)};
  };
  // 2. Posts, rings and braces.
  for (int s = 0; s < storeys; ++s)
    for (int c = 0; c < 4; ++c) {
      const int c1 = (c + 1) % 4;
      add_beam(mesh, corner(s, c), corner(s + 1, c), 1.3f * width);
      add_beam(mesh, corner(s + 1, c), corner(s + 1, c1), width);
      add_beam(mesh, corner(s, c), corner(s + 1, c1), 0.8f * width);
      if (x_braces) add_beam(mesh, corner(s, c1), corner(s + 1, c), 0.8f * width);
    }
  // 3. A cross arm two storeys from the top, out over two faces.
  const int arm = std::max(1, storeys - 2);
  const Vec3f a0 = corner(arm, 0), a1 = corner(arm, 1);
  const float reach = static_cast<float>(base * (0.5 + 0.3 * random.uniform()));
  add_beam(mesh, a0 - Vec3f{reach, 0, 0}, a1 + Vec3f{reach, 0, 0}, width);
  add_beam(mesh, a0 - Vec3f{reach, 0, 0}, corner(arm + 1, 0), 0.8f * width);
  add_beam(mesh, a1 + Vec3f{reach, 0, 0}, corner(arm + 1, 1), 0.8f * width);
  // 4. One material: painted steel, opaque.
  SurfaceMaterial steel;
  steel.name = "steel";
  steel.base_color = {0.45f, 0.18f, 0.12f, 1};
  mesh.materials = {steel};
  mesh.triangle_materials.assign(mesh.triangles.size(), 0);
  return mesh;
}

}  // namespace qf
