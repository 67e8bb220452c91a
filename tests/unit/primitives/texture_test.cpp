// Texture resampling (thesis 3.3): interpolation, concavities, radial profiles, colour extension,
// partition of unity across overlapping domains.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "primitives/support.h"
#include "primitives/texture.h"

namespace qf {
namespace {

struct Scene {
  std::vector<Vec3f> positions, normals;
  std::vector<Rgb8> colors;
  std::vector<float> radii;
  SparseMatrix psi;
};

// Points on a grid over [0, 2]^2 in the plane z = 0 (radius = spacing), red = 255 x / 2; `keep` decides
// which grid points exist. Psi: column 0 = 1 - x/2, column 1 = x/2 (two overlapping functions).
template <class Keep>
Scene grid(Keep keep, float spacing = 0.05f) {
  Scene s;
  std::vector<std::int32_t> outer{0}, inner;
  std::vector<double> values;
  const int steps = static_cast<int>(std::lround(2.0f / spacing));
  for (int y = 0; y <= steps; ++y)
    for (int x = 0; x <= steps; ++x) {
      const float px = spacing * x, py = spacing * y;
      if (!keep(px, py)) continue;
      s.positions.push_back({px, py, 0});
      s.normals.push_back({0, 0, 1});
      s.radii.push_back(spacing);
      s.colors.push_back({static_cast<std::uint8_t>(std::lround(127.5f * px)), 50, 100});
      inner.push_back(0), values.push_back(1.0 - px / 2);
      inner.push_back(1), values.push_back(px / 2);
      outer.push_back(static_cast<std::int32_t>(inner.size()));
    }
  s.psi = from_rows(static_cast<Eigen::Index>(s.positions.size()), 2, outer, inner, values);
  return s;
}

// The texel holding world point (x, y, 0): its RGBA, and (in `center`) the world position of
// its centre.
std::array<int, 4> texel_at(const Texture& t, const SupportRect& r, float x, float y, Vec3f* center = nullptr) {
  const Vec3f d = Vec3f{x, y, 0} - r.center;
  const int i = static_cast<int>(std::floor((dot(d, r.axis_u) + 0.5f * t.width * t.texel) / t.texel));
  const int j = static_cast<int>(std::floor((dot(d, r.axis_v) + 0.5f * t.height * t.texel) / t.texel));
  if (center)
    *center = r.center + r.axis_u * ((i + 0.5f) * t.texel - 0.5f * t.width * t.texel) +
              r.axis_v * ((j + 0.5f) * t.texel - 0.5f * t.height * t.texel);
  const std::size_t k = 4 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(i));
  return {t.rgba[k], t.rgba[k + 1], t.rgba[k + 2], t.rgba[k + 3]};
}

TEST(Texture, LinearAffineInterpolatesColourAndWeight) {
  const Scene s = grid([](float, float) { return true; });
  DomainOptions all;
  all.tau = 0.0;  // every point in both domains
  const Domains d = make_domains(s.psi, all);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r);
  EXPECT_NEAR(t.texel, 0.05f, 1e-6f);
  EXPECT_EQ(t.width, 42);  // 2 + 2 radii over 0.05
  for (float x : {0.3f, 0.8f, 1.37f, 1.9f}) {
    Vec3f at;
    const auto c = texel_at(t, r, x, 0.77f, &at);
    // Red is the Psi_0-weighted linear interpolation of the grid points' reds: every triangle has
    // its corners at the two grid columns x0 <= x < x0 + 0.05, holding the share t of the weight.
    const double x0 = 0.05 * std::floor(at.x / 0.05), share = (at.x - x0) / 0.05;
    const double w0 = (1 - share) * (1 - x0 / 2), w1 = share * (1 - (x0 + 0.05) / 2);
    const double red = (w0 * std::lround(127.5 * x0) + w1 * std::lround(127.5 * (x0 + 0.05))) / (w0 + w1);
    EXPECT_NEAR(c[0], red, 1.0) << "x " << at.x;
    EXPECT_NEAR(c[3], 255 * (1 - at.x / 2), 1.0) << "x " << at.x;  // alpha follows Psi_0
  }
  EXPECT_GT(t.covered, static_cast<std::size_t>(40 * 40));
}

TEST(Texture, PartitionOfUnityAcrossDomains) {
  const Scene s = grid([](float, float) { return true; });
  DomainOptions all;
  all.tau = 0.0;
  const Domains d = make_domains(s.psi, all);
  SupportRect r0 = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  SupportRect r1 = r0;
  r1.domain = 1;  // the same rectangle for both functions: texels line up
  const Texture t0 = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r0);
  const Texture t1 = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r1);
  for (float x = 0.1f; x < 1.95f; x += 0.13f)
    for (float y = 0.1f; y < 1.95f; y += 0.17f)
      EXPECT_NEAR(texel_at(t0, r0, x, y)[3] + texel_at(t1, r0, x, y)[3], 255, 2) << x << "," << y;
}

// Mesh inputs store alpha as 1 - (1 - Psi)^e (TextureOptions::alpha_exponent): every texel's alpha
// is the encoded Psi of the plain texture, colours unchanged, and a runtime's decoding gives Psi back.
TEST(Texture, AlphaExponentEncodesPsiInvertibly) {
  const Scene s = grid([](float, float) { return true; });
  DomainOptions all;
  all.tau = 0.0;
  const Domains d = make_domains(s.psi, all);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  TextureOptions sharp;
  sharp.alpha_exponent = 2;
  const Texture plain = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r);
  const Texture encoded = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, sharp);
  ASSERT_EQ(plain.rgba.size(), encoded.rgba.size());
  for (std::size_t k = 0; k < plain.rgba.size(); k += 4) {
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(plain.rgba[k + c], encoded.rgba[k + c]) << k;
    // (the plain texel's rounding, up to 1/2, doubles where the encoding's slope is 2)
    EXPECT_NEAR(encoded.rgba[k + 3], 255 * encode_alpha(plain.rgba[k + 3] / 255.0, 2), 1.5) << k;
  }
  // Psi = 0.5 is stored as 0.75; the seams' Psi of 0.163 lands on the mesh cutoff 0.3.
  EXPECT_DOUBLE_EQ(encode_alpha(0.5, 2), 0.75);
  EXPECT_NEAR(encode_alpha(0.163, 2), 0.3, 0.001);
  for (double psi : {0.0, 0.1, 0.37, 0.8, 1.0}) EXPECT_NEAR(decode_alpha(encode_alpha(psi, 2), 2), psi, 1e-12) << psi;
  EXPECT_DOUBLE_EQ(encode_alpha(0.3, 1), 0.3);
}

TEST(Texture, ConcavitiesStayEmptyAndColoursExtend) {
  // An L: the quadrant x > 1, y > 1 has no points. Delaunay triangles across it have edges much
  // longer than two radii and are dropped.
  const Scene s = grid([](float x, float y) { return !(x > 1.01f && y > 1.01f); });
  const Domains d = make_domains(s.psi);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r);
  const auto empty = texel_at(t, r, 1.6f, 1.6f);
  EXPECT_EQ(empty[3], 0);
  EXPECT_GT(empty[0] + empty[1] + empty[2], 0);  // colour extended from the nearest texel, not black
  EXPECT_GT(texel_at(t, r, 0.6f, 1.6f)[3], 100);
  TextureOptions plain;
  plain.extend_colors = false;
  const auto black = texel_at(resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, plain), r, 1.6f, 1.6f);
  EXPECT_EQ(black[0] + black[1] + black[2] + black[3], 0);
}

// The texture's alpha at world point (x, y, 0) as an engine samples it: bilinear between texel
// centres, clamped to the outer texels.
double filtered_alpha(const Texture& t, const SupportRect& r, double x, double y) {
  const Vec3f d = Vec3f{static_cast<float>(x), static_cast<float>(y), 0} - r.center;
  const double fi = std::clamp((dot(d, r.axis_u) + 0.5 * t.width * t.texel) / t.texel - 0.5, 0.0, t.width - 1.0);
  const double fj = std::clamp((dot(d, r.axis_v) + 0.5 * t.height * t.texel) / t.texel - 0.5, 0.0, t.height - 1.0);
  const int i = std::min(static_cast<int>(fi), t.width - 2), j = std::min(static_cast<int>(fj), t.height - 2);
  const double a = fi - i, b = fj - j;
  auto at = [&](int u, int v) { return t.rgba[4 * (static_cast<std::size_t>(v) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(u)) + 3] / 255.0; };
  return (1 - b) * ((1 - a) * at(i, j) + a * at(i + 1, j)) + b * ((1 - a) * at(i, j + 1) + a * at(i + 1, j + 1));
}

// A disc of points with Psi 1: 17 rings 0.05 apart about (1, 1), points 0.05 apart on each; a
// point's radius is radius(its distance from the centre).
template <class Radius>
Scene disc(Radius radius) {
  Scene s;
  std::vector<std::int32_t> outer{0}, inner;
  std::vector<double> values;
  for (int ring = 0; ring <= 16; ++ring) {
    const int count = std::max(1, static_cast<int>(std::lround(2 * 3.14159265 * ring)));
    for (int c = 0; c < count; ++c) {
      const double a = 2 * 3.14159265 * c / count;
      const float px = static_cast<float>(1 + 0.05 * ring * std::cos(a)), py = static_cast<float>(1 + 0.05 * ring * std::sin(a));
      s.positions.push_back({px, py, 0});
      s.normals.push_back({0, 0, 1});
      s.radii.push_back(radius(0.05 * ring));
      s.colors.push_back({200, 50, 100});
      inner.push_back(0), values.push_back(1.0);
      outer.push_back(static_cast<std::int32_t>(inner.size()));
    }
  }
  s.psi = from_rows(static_cast<Eigen::Index>(s.positions.size()), 1, outer, inner, values);
  return s;
}

// Sub-texel edges (TextureOptions::edge_cutoff): a disc of points (radius 0.8, spacing 0.05,
// point radius 0.05, Psi 1) on texels of 0.23, 4.6 spacings. Along 24 directions, an alpha test at
// the cutoff on the filtered alpha cuts where the support ends (edge_radius x 0.05 past the
// outermost points) to 0.15 texel (measured: -0.02..+0.12; outward where the texels around the
// cut reach past the ramp's zero); the interior keeps its Psi. Without the ramp the cut lay
// -0.1..+0.36 texel off the fallback discs' edge, and +1.5 towards the rectangle's corners.
TEST(Texture, EdgeRampCutsOnTheSupportEdge) {
  // Rings 0.05 apart about (1, 1), points 0.05 apart on each: the outline is a circle of 0.8.
  const Scene s = disc([](double) { return 0.05f; });
  const Domains d = make_domains(s.psi);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  TextureOptions o;
  o.min_texel = 0.23;
  o.edge_cutoff = 0.3;
  const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, o);
  EXPECT_EQ(t.width, static_cast<int>(std::ceil(2 * r.half_u / 0.23)) + 2);  // a texel more on every side
  const double rho = o.edge_radius * 0.05;
  for (int k = 0; k < 24; ++k) {
    const double cs = std::cos(0.2618 * k + 0.1), sn = std::sin(0.2618 * k + 0.1);
    // The support's edge along the ray: the last distance within rho of a point (the kept
    // triangles lie inside the discs here: the outline's edges are at most 0.071 long).
    double edge = 0, cut = 0;
    for (double u = 0.5; u < 1.2; u += 0.0005) {
      const double x = 1 + u * cs, y = 1 + u * sn;
      double nearest = 1e9;
      for (const Vec3f& p : s.positions) nearest = std::min(nearest, std::hypot(x - p.x, y - p.y));
      if (nearest <= rho) edge = u;
      if (filtered_alpha(t, r, x, y) >= 0.3) cut = u;
    }
    EXPECT_NEAR(cut, edge, 0.15 * 0.23) << "direction " << k;
    // Three texels inside, past the ramp's (1 - 0.3) / 0.5 = 1.4 texels: Psi itself.
    EXPECT_NEAR(filtered_alpha(t, r, 1 + (edge - 0.69) * cs, 1 + (edge - 0.69) * sn), 1.0, 0.01) << "direction " << k;
  }
}

// An unevenly sampled face: the points within 0.15 of the centre have radius 0.02, so the
// triangles among them (edges 0.05 > 0.02 + 0.02) are not kept, and the outline has an inner loop
// there; the splats leave parts of it uncovered. The gap joins the support and alpha keeps its Psi
// there, as across the rest of the face; without edge_gap the ramp cuts a hole into it.
TEST(Texture, EdgeRampKeepsGapsBetweenTriangles) {
  const Scene s = disc([](double rho) { return rho < 0.16 ? 0.02f : 0.05f; });
  const Domains d = make_domains(s.psi);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  TextureOptions o;
  o.min_texel = 0.02;
  o.edge_cutoff = 0.3;
  const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, o);
  for (const double u : {0.0, 0.03, 0.06, 0.09})
    for (int k = 0; k < 8; ++k)
      EXPECT_NEAR(filtered_alpha(t, r, 1 + u * std::cos(0.785 * k), 1 + u * std::sin(0.785 * k)), 1.0, 0.02)
          << "at " << u << ", direction " << k;
  o.edge_gap = 0;
  const Texture cut = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, o);
  double lowest = 1;
  for (double u = 0; u < 0.15; u += 0.005) lowest = std::min(lowest, filtered_alpha(cut, r, 1 + u, 1.0));
  EXPECT_LT(lowest, 0.3);  // measured: 0.23, 0.06 from the centre
}

TEST(Texture, RadialProfiles) {
  const Scene s = grid([](float, float) { return true; });
  const Domains d = make_domains(s.psi);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  for (RadialProfile p : {RadialProfile::kConstant, RadialProfile::kLinear, RadialProfile::kGaussian}) {
    TextureOptions o;
    o.method = ResampleMethod::kRadial;
    o.profile = p;
    o.width = 2.0f;
    const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, o);
    // Inside, the profiles overlap (f >= 1): alpha is the normalised Psi_0 = 1 - x/2.
    EXPECT_NEAR(texel_at(t, r, 0.52f, 1.0f)[3], 255 * (1 - 0.52 / 2), 12) << int(p);
    EXPECT_NEAR(texel_at(t, r, 0.52f, 1.0f)[0], 127.5 * 0.52, 12) << int(p);
  }
  // Without colours, the base colour.
  TextureOptions o;
  const Texture t = resample_texture(s.positions, {}, {}, s.radii, s.psi, d, r, o);
  const auto c = texel_at(t, r, 1.0f, 1.0f);
  EXPECT_EQ(c[0], 200);
  EXPECT_EQ(c[1], 200);
}

TEST(Texture, NormalMapInTangentSpace) {
  // Normals tilted towards +x by 30 degrees on the left half, straight up on the right half.
  Scene s = grid([](float, float) { return true; });
  const float tilt = 3.14159265f / 6;
  for (std::size_t i = 0; i < s.positions.size(); ++i)
    s.normals[i] = s.positions[i].x < 1.0f ? Vec3f{std::sin(tilt), 0, std::cos(tilt)} : Vec3f{0, 0, 1};
  const Domains d = make_domains(s.psi);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  const Texture t = resample_texture(s.positions, s.colors, s.normals, s.radii, s.psi, d, r);
  ASSERT_EQ(t.normals.size(), t.rgba.size());
  auto normal_at = [&](float x, float y) {
    Vec3f at;
    texel_at(t, r, x, y, &at);
    const Vec3f dd = at - r.center;
    const int i = static_cast<int>(std::floor((dot(dd, r.axis_u) + 0.5f * t.width * t.texel) / t.texel));
    const int j = static_cast<int>(std::floor((dot(dd, r.axis_v) + 0.5f * t.height * t.texel) / t.texel));
    const std::size_t k = 4 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(i));
    auto dec = [&](int c) { return t.normals[k + static_cast<std::size_t>(c)] / 127.5f - 1.0f; };
    // Back to world space through the tangent frame.
    return r.axis_u * dec(0) + r.axis_v * dec(1) + r.normal * dec(2);
  };
  const Vec3f left = normal_at(0.4f, 1.0f), right = normal_at(1.6f, 1.0f);
  EXPECT_NEAR(left.x, std::sin(tilt), 0.02f);
  EXPECT_NEAR(left.z, std::cos(tilt), 0.02f);
  EXPECT_NEAR(right.z, 1.0f, 0.02f);
  EXPECT_TRUE(resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r).normals.empty());
}

TEST(Texture, MaxSideLimitsTheGrid) {
  const Scene s = grid([](float, float) { return true; });
  const Domains d = make_domains(s.psi);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  TextureOptions o;
  o.max_side = 16;
  const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, o);
  EXPECT_LE(std::max(t.width, t.height), 16);
  EXPECT_GT(t.texel, 0.05f);
}

// A domain with many points a texel (a coarse level of a dense set) is merged per third of a
// texel before the resampling; its texture is the one its surface gives at an ordinary density.
// The L of ConcavitiesStayEmptyAndColoursExtend at 10x the density (0.005 apart, 120k points) and
// at the grid's (0.05), both on texels of 0.1: ~30 points a texel against ~0.3.
TEST(Texture, DenseDomainsShowTheirSurface) {
  const auto l_shape = [](float x, float y) { return !(x > 1.01f && y > 1.01f); };
  const Scene sparse = grid(l_shape), dense = grid(l_shape, 0.005f);
  TextureOptions o;
  o.min_texel = 0.1;
  const Domains dd = make_domains(dense.psi), ds = make_domains(sparse.psi);
  SupportRect r = support_rectangles(sparse.positions, sparse.normals, sparse.radii, sparse.psi, ds)[0];
  const Texture a = resample_texture(dense.positions, dense.colors, dense.normals, dense.radii, dense.psi, dd, r, o);
  const Texture b = resample_texture(sparse.positions, sparse.colors, sparse.normals, sparse.radii, sparse.psi, ds, r, o);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  EXPECT_EQ(texel_at(a, r, 1.6f, 1.6f)[3], 0);  // the concavity stays empty
  EXPECT_GT(texel_at(a, r, 0.6f, 1.6f)[3], 100);
  int worst_alpha = 0, worst_red = 0;
  for (float y = 0.15f; y < 1.9f; y += 0.1f)
    for (float x = 0.15f; x < 1.9f; x += 0.1f) {
      // Texels of the L (the rectangle may not reach the concavity's far corner), away from the
      // concavity's edges, where the ramp depends on the spacing.
      if (!l_shape(x, y) || std::fabs(x - 1.0f) < 0.15f || std::fabs(y - 1.0f) < 0.15f) continue;
      const auto p = texel_at(a, r, x, y), q = texel_at(b, r, x, y);
      worst_alpha = std::max(worst_alpha, std::abs(p[3] - q[3]));
      if (q[3] > 0) worst_red = std::max(worst_red, std::abs(p[0] - q[0]));
    }
  EXPECT_LE(worst_alpha, 3);
  EXPECT_LE(worst_red, 3);
  // Coverage as the L's area (3) gives: the sparse grid's splats reach half a spacing beyond it
  // (328 texels), the dense points' edges lie on it (297 unmerged).
  EXPECT_NEAR(double(a.covered), 3.0 / (0.1 * 0.1), 0.05 * 300);
}

// A mesh input's quad shows the mesh itself (issue 31): a square [0, 1] x [0, 2] of two triangles
// with a two-texel texture (red below y = 1, blue above) under the grid's points, which are green.
// The texture's colours show, not the points'; alpha is the mesh's coverage where it covers less
// than Psi (nothing right of x = 1); the normal map is the mesh's normals.
TEST(Texture, MeshSurfaceShowsTheMeshItself) {
  const Scene s = grid([](float, float) { return true; });
  std::vector<Rgb8> green(s.positions.size(), Rgb8{0, 255, 0});
  DomainOptions all;
  all.tau = 0.0;
  const Domains d = make_domains(s.psi, all);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 2, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.corner_uvs = {{Vec2f{0, 1}, Vec2f{1, 1}, Vec2f{1, 0}}, {Vec2f{0, 1}, Vec2f{1, 0}, Vec2f{0, 0}}};
  mesh.textures = {TextureImage{1, 2, {0, 0, 255, 255, 255, 0, 0, 255}}};  // row 0 (v = 0, top): blue
  SurfaceMaterial m;
  m.texture = 0;
  m.wrap_s = m.wrap_t = TextureWrap::kClampToEdge;
  mesh.materials = {m};
  mesh.triangle_materials = {0, 0};
  MeshSurface surface;
  surface.mesh = &mesh;
  surface.normals = {{0, 0.6f, 0.8f}, {0, 0.6f, 0.8f}, {0, 0.6f, 0.8f}, {0, 0.6f, 0.8f}};
  for (const Vec3f& p : s.positions) surface.point_triangles.push_back(p.x >= p.y / 2 ? 0u : 1u);
  const std::vector<Vec3f> flat(s.positions.size(), Vec3f{0, 0, 1});
  const Texture t = resample_texture(s.positions, green, flat, s.radii, s.psi, d, r, {}, &surface);
  const auto at = [&](float x, float y) { return texel_at(t, r, x, y); };
  for (float x : {0.2f, 0.7f}) {
    EXPECT_GT(at(x, 0.3f)[0], 250) << x;  // red: the texture, bilinear between its two texels near y = 1
    EXPECT_LT(at(x, 0.3f)[1], 5) << x;
    EXPECT_GT(at(x, 1.7f)[2], 250) << x;
    Vec3f centre;
    texel_at(t, r, x, 1.7f, &centre);
    EXPECT_NEAR(at(x, 1.7f)[3], 255 * (1 - centre.x / 2), 1.0) << x;  // covered: Psi_0
  }
  EXPECT_EQ(at(1.3f, 1.0f)[3], 0);  // no mesh there
  EXPECT_EQ(at(1.8f, 0.5f)[3], 0);
  // The mesh's normal, (0, 0.6, 0.8) in the quad's frame, up to the frame's sign along its axes.
  const Vec3f n = {0, 0.6f, 0.8f};
  const Vec3f c = Vec3f{0.5f, 1.0f, 0} - r.center;
  const int i = static_cast<int>(std::floor((dot(c, r.axis_u) + 0.5f * t.width * t.texel) / t.texel));
  const int j = static_cast<int>(std::floor((dot(c, r.axis_v) + 0.5f * t.height * t.texel) / t.texel));
  const std::size_t k = 4 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(i));
  const double nu = t.normals[k] / 127.5 - 1, nv = t.normals[k + 1] / 127.5 - 1, nz = t.normals[k + 2] / 127.5 - 1;
  EXPECT_NEAR(nu, dot(n, r.axis_u), 0.02);
  EXPECT_NEAR(nv, dot(n, r.axis_v), 0.02);
  EXPECT_NEAR(nz, dot(n, r.normal), 0.02);
}

// Coverage is the share of a texel the surface covers: a strip 0.3 texels wide across the grid
// gives its texels partial alpha (coverage_gain x 0.3 encoded), the texels beside it none.
TEST(Texture, MeshSurfaceCoverageIsFractional) {
  const Scene s = grid([](float, float) { return true; });
  DomainOptions all;
  all.tau = 0.0;
  const Domains d = make_domains(s.psi, all);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  // The strip covers x in [0.5 + 0.01, 0.5 + 0.025] of texels 0.05 wide: from the grid, texel
  // centres at 0.05 k - 0.025 (one texel of room), so the texel [0.5, 0.55] holds it whole.
  TriangleMesh mesh;
  mesh.positions = {{0.51f, -0.1f, 0}, {0.525f, -0.1f, 0}, {0.525f, 2.1f, 0}, {0.51f, 2.1f, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  MeshSurface surface;
  surface.mesh = &mesh;
  surface.point_triangles.assign(s.positions.size(), 0);
  surface.point_triangles[0] = 1;
  TextureOptions o;
  o.coverage_samples = 20;  // 0.015 / 0.05 x 20 = 6 of 20 columns
  o.coverage_gain = 2;
  const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, o, &surface);
  const auto a = [&](float x) { return texel_at(t, r, x, 1.0f)[3]; };
  const double psi = 255 * (1 - 0.525 / 2);
  EXPECT_NEAR(a(0.52f), std::min(psi, 255 * 2 * 0.3), 2);
  EXPECT_EQ(a(0.47f), 0);
  EXPECT_EQ(a(0.58f), 0);
}

// A sparse quad (issue 49) is painted with coarser texels: the strip fills a few of the texels Psi
// shows, so with sparse_fill 0.7 its texels are sparse_texel_factor x min_texel; a square that
// fills them keeps min_texel.
TEST(Texture, SparseQuadsGetCoarserTexels) {
  const Scene s = grid([](float, float) { return true; });
  DomainOptions all;
  all.tau = 0.0;
  const Domains d = make_domains(s.psi, all);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  TextureOptions o;
  o.coverage_samples = 20;  // subsamples 0.004 apart: the strip covers ~19% of its texels
  o.coverage_gain = 2;
  o.min_texel = 0.08;
  o.sparse_fill = 0.7;
  o.sparse_texel_factor = 2;
  TriangleMesh strip;
  strip.positions = {{0.51f, -0.1f, 0}, {0.525f, -0.1f, 0}, {0.525f, 2.1f, 0}, {0.51f, 2.1f, 0}};
  strip.triangles = {{0, 1, 2}, {0, 2, 3}};
  TriangleMesh square = strip;
  square.positions = {{-0.1f, -0.1f, 0}, {2.1f, -0.1f, 0}, {2.1f, 2.1f, 0}, {-0.1f, 2.1f, 0}};
  for (const TriangleMesh* mesh : {&strip, &square}) {
    MeshSurface surface;
    surface.mesh = mesh;
    surface.point_triangles.assign(s.positions.size(), 0);
    surface.point_triangles[0] = 1;
    const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, o, &surface);
    EXPECT_FLOAT_EQ(t.texel, mesh == &strip ? 0.16f : 0.08f);
  }
  // Off (sparse_fill 0), the strip keeps min_texel.
  o.sparse_fill = 0;
  MeshSurface surface;
  surface.mesh = &strip;
  surface.point_triangles.assign(s.positions.size(), 0);
  EXPECT_FLOAT_EQ(resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, o, &surface).texel, 0.08f);
}

// A quad shows the surface nearest its front (the side its normal points to): of two squares
// 0.01 apart, within the slab, the one in front gives the colour, whichever is listed first.
TEST(Texture, MeshSurfaceShowsTheNearestFragment) {
  const Scene s = grid([](float, float) { return true; });
  DomainOptions all;
  all.tau = 0.0;
  const Domains d = make_domains(s.psi, all);
  const SupportRect r = support_rectangles(s.positions, s.normals, s.radii, s.psi, d)[0];
  ASSERT_GT(r.normal.z, 0.99f);
  for (const float red_z : {0.01f, -0.01f}) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, red_z}, {2, 0, red_z}, {2, 2, red_z}, {0, 2, red_z}};
    mesh.triangles = {{4, 5, 6}, {4, 6, 7}, {0, 1, 2}, {0, 2, 3}};
    SurfaceMaterial red, blue;
    red.base_color = {1, 0, 0, 1};
    blue.base_color = {0, 0, 1, 1};
    mesh.materials = {red, blue};
    mesh.triangle_materials = {0, 0, 1, 1};
    MeshSurface surface;
    surface.mesh = &mesh;
    for (std::size_t i = 0; i < s.positions.size(); ++i) surface.point_triangles.push_back(static_cast<std::uint32_t>(i % 4));
    const Texture t = resample_texture(s.positions, s.colors, {}, s.radii, s.psi, d, r, {}, &surface);
    const auto c = texel_at(t, r, 0.6f, 1.3f);
    EXPECT_EQ(c[0], red_z > 0 ? 255 : 0) << red_z;
    EXPECT_EQ(c[2], red_z > 0 ? 0 : 255) << red_z;
  }
}

}  // namespace
}  // namespace qf
