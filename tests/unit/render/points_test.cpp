// Point impostors (paper 5): the seeded permutation, the .glb round trip (order and colours kept),
// the number of points drawn by distance, and renders against the mesh: the thinned points cover
// the mesh's silhouette, and nearer than s Z0 they fade to the mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "gl/egl.h"
#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "analysis/analysis.h"
#include "gltf/glb.h"
#include "primitives/texture.h"
#include "runtime_gl/camera.h"
#include "runtime_gl/draw_gl11.h"
#include "runtime_gl/loader.h"
#include "measure/reference_scene.h"
#include "sample/sample.h"
#include "shapes/shapes.h"

namespace qf::render {
namespace {

// The runtime blends Psi: a level written with alphaExponent (mesh inputs) loads with the same
// alpha as the level written with Psi itself, within the 8-bit rounding of the two encodings.
TEST(ImpostorLoader, DecodesTheAlphaExponent) {
  const PointSet p = generate_shape("octahedron");
  const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
  const std::size_t level = h.level_count() - 2;
  const SparseMatrix psi = basis_at_level(h, level);
  const Domains d = make_domains(psi);
  const std::vector<SupportRect> rects = support_rectangles(p.positions, p.normals, p.radii, psi, d);
  auto written = [&](double exponent) {
    TextureOptions o;
    o.alpha_exponent = exponent;
    std::vector<Texture> textures;
    for (const SupportRect& r : rects) textures.push_back(resample_texture(p.positions, p.colors, p.normals, p.radii, psi, d, r, o));
    ImpostorLevel il = make_impostor_level(level, rects, textures, d);
    il.alpha_exponent = exponent;
    return load_baked(encode_glb(il), "level.glb").impostor;
  };
  const ImpostorScene plain = written(1), sharp = written(2);
  ASSERT_EQ(plain.textures.size(), sharp.textures.size());
  int worst = 0;
  for (std::size_t t = 0; t < plain.textures.size(); ++t)
    for (std::size_t k = 3; k < plain.textures[t].rgba.size(); k += 4) {
      const int a = plain.textures[t].rgba[k], b = sharp.textures[t].rgba[k];
      worst = std::max(worst, std::abs(a - b));
    }
  // Near Psi = 1 the stored alpha is flat (1 - (1 - Psi)^2), so one stored step spans several.
  // Undecoded, Psi = 0.5 would load as 191 instead of 128.
  EXPECT_LE(worst, 12);
}

TEST(PointImpostor, PermutationIsSeededAndComplete) {
  const auto a = point_permutation(1000, 7), b = point_permutation(1000, 7), c = point_permutation(1000, 8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  auto sorted = a;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < 1000; ++i) ASSERT_EQ(sorted[i], i);
  // Evenly thinned: the first tenth holds about a tenth of each half of the input.
  const auto low = std::count_if(a.begin(), a.begin() + 100, [](std::uint32_t i) { return i < 500; });
  EXPECT_NEAR(double(low), 50.0, 15.0);
}

TEST(PointImpostor, PointsToDrawFollowsTheInverseSquare) {
  // s Z0 = 0.01 * 512 / (2 tan 15 deg) = 9.55: all points there and nearer, a quarter at twice that.
  Camera c;
  c.height = 512;
  c.fovy_degrees = 30;
  const double z0 = c.focal_pixels();
  EXPECT_NEAR(z0, 955.4, 0.1);
  const float d0 = static_cast<float>(0.01 * z0);
  EXPECT_EQ(points_to_draw(10000, 0.01f, d0 * 0.5f, z0), 10000u);
  EXPECT_NEAR(double(points_to_draw(10000, 0.01f, d0 * 2, z0)), 2500.0, 2.0);
  EXPECT_NEAR(double(points_to_draw(10000, 0.01f, d0 * 10, z0)), 100.0, 1.0);
}

struct Fixture {
  TriangleMesh mesh = generate_mesh("sphere", 12);
  SampleStats stats;
  PointSet points;
  std::string path;
  Fixture() {
    SampleOptions o;
    o.backend = "cpu";
    o.ldi_size = 256;
    const PointSet sampled = sample_mesh(mesh, o, "sphere", &stats);
    points = permuted(sampled, point_permutation(sampled.size(), 3));
    PointImpostorInfo info;
    info.pixel = stats.pixel;
    info.seed = 3;
    const std::vector<std::uint8_t> glb = encode_point_glb(points, info);
    path = (std::filesystem::temp_directory_path() / ("qf_points_" + std::to_string(::getpid()) + ".glb")).string();
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()), static_cast<std::streamsize>(glb.size()));
  }
  ~Fixture() { std::filesystem::remove(path); }
};

TEST(PointImpostor, GlbRoundTripKeepsOrderAndColours) {
  Fixture f;
  const BakedScene b = load_baked(f.path);
  ASSERT_EQ(b.kind, BakedScene::kPoints);
  const PointImpostorScene* s = &b.points;
  EXPECT_FLOAT_EQ(s->pixel, f.stats.pixel);
  ASSERT_EQ(s->positions.size(), f.points.size());
  EXPECT_TRUE(s->positions == f.points.positions);
  int worst = 0;
  for (std::size_t i = 0; i < s->colors.size(); ++i) {
    worst = std::max(worst, std::abs(int(s->colors[i].r) - int(f.points.colors[i].r)));
    worst = std::max(worst, std::abs(int(s->colors[i].g) - int(f.points.colors[i].g)));
  }
  EXPECT_LE(worst, 1);  // sRGB -> 16-bit linear -> sRGB
}

// Share of the mesh's pixels the other image covers (non-background), and of its own pixels.
double covered_share(const Image& mesh, const Image& other) {
  std::size_t in = 0, both = 0;
  for (std::size_t p = 0; p < mesh.rgba.size(); p += 4) {
    const bool m = mesh.rgba[p] | mesh.rgba[p + 1] | mesh.rgba[p + 2], o = other.rgba[p] | other.rgba[p + 1] | other.rgba[p + 2];
    in += m;
    both += m && o;
  }
  return in ? double(both) / double(in) : 0.0;
}

TEST(PointImpostor, ThinnedPointsCoverTheMeshAndFadeToItWhenNear) {
  Fixture f;
  const PointImpostorScene scene = load_baked(f.path).points;
  const MeshScene mesh = mesh_scene(f.mesh, "sphere");
  HeadlessContext context;
  const int size = 256;
  Renderer points_r(size, size), mesh_r(size, size);
  points_r.set_scene(scene, &mesh);
  mesh_r.set_scene(mesh);
  const Sphere sphere = bounding_sphere(mesh.bounds);
  Camera unit;  // only for the focal length in pixels
  unit.height = size;
  const double d_switch = scene.pixel * unit.focal_pixels();  // fovy 30, as the cameras below
  DrawSettings s;
  // Far: a fraction of the points, still covering the sphere's disc.
  for (double factor : {1.5, 3.0}) {
    const Camera c = orbit_camera(sphere, orbit_direction(30, 20), static_cast<float>(d_switch * factor), size, size, 30);
    const DrawStats st = points_r.draw(c, s);
    const Image pts = points_r.read_pixels();
    mesh_r.draw(c, s);
    const Image ref = mesh_r.read_pixels();
    EXPECT_LT(st.points, scene.positions.size()) << factor;
    EXPECT_NEAR(double(st.points), double(scene.positions.size()) / (factor * factor), 0.02 * double(scene.positions.size()));
    EXPECT_GT(covered_share(ref, pts), 0.97) << "distance " << factor << " s Z0";
    // 2.5-pixel points reach ~1.25 pixels past the silhouette: 6% of a 42-pixel disc at 3 s Z0.
    EXPECT_GT(covered_share(pts, ref), 0.9) << "no points outside the mesh's silhouette";
    EXPECT_EQ(st.points_weight, 1.0f);
  }
  // Near: the mesh alone at 0.6 s Z0, fading in between.
  Camera c = orbit_camera(sphere, orbit_direction(30, 20), static_cast<float>(d_switch * 0.6), size, size, 30);
  EXPECT_EQ(points_r.draw(c, s).points_weight, 0.0f);
  const Image near_pts = points_r.read_pixels();
  mesh_r.draw(c, s);
  EXPECT_EQ(near_pts.rgba, mesh_r.read_pixels().rgba);
  c = orbit_camera(sphere, orbit_direction(30, 20), static_cast<float>(d_switch * 0.85), size, size, 30);
  const float w = points_r.draw(c, s).points_weight;
  EXPECT_GT(w, 0.3f);
  EXPECT_LT(w, 0.7f);
}

// A recommended chain may end in the point impostor: combined into one MSFT_lod file after a mesh
// LOD, it loads (the item view has no triangles to show there) and the engine draws either level.
TEST(PointImpostor, CombinedLodFileWithAPointPartLoadsAndDraws) {
  Fixture f;
  std::ifstream in(f.path, std::ios::binary);
  const std::vector<std::uint8_t> points_glb((std::istreambuf_iterator<char>(in)), {});
  const std::vector<std::uint8_t> mesh_glb = encode_mesh_glb(f.mesh, true);
  const std::vector<std::uint8_t> combined = combine_lod_glb({&mesh_glb, &points_glb}, {0.05, 0}, "chain");
  const BakedScene b = load_baked(combined, "chain_lods.glb");
  ASSERT_EQ(b.lods.size(), 2u);
  EXPECT_EQ(b.lod_coverage, (std::vector<double>{0.05, 0}));
  EXPECT_TRUE(b.lods[1].impostor.items.empty());
  EXPECT_FALSE(b.lods[1].impostor.bounds.empty());
  HeadlessContext context;
  Renderer r(64, 64);
  DrawSettings s;
  s.method = Method::kEngine;
  for (const BakedScene& level : b.lods) {
    r.set_engine_scene(level.engine);
    const Sphere sphere = bounding_sphere(level.impostor.bounds);
    r.draw(orbit_camera(sphere, orbit_direction(30, 20), 0, 64, 64), s);
    const Image img = r.read_pixels();
    std::size_t lit = 0;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4) lit += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2] > 0;
    EXPECT_GT(lit, 64u * 64u / 5) << "a level of the combined file draws";
  }
}

}  // namespace
}  // namespace qf::render
