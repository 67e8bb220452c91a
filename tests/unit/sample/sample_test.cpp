// Depth-peeled mesh sampling (baker/sample): point counts against projected areas, points on the
// surface, even layer counts on closed meshes, GL against the CPU reference, the per-axis variant,
// density across axis-set borders, determinism, bad meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <tuple>

#include "analysis/neighborhoods.h"
#include "core/error.h"
#include "io/model_io.h"
#include "core/color.h"
#include "sample/sample.h"
#include "sample/surface_color.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

SampleOptions options(const std::string& backend, int ldi = 200) {
  SampleOptions o;
  o.backend = backend;
  o.ldi_size = ldi;
  return o;
}

// The expected point count: each triangle's area projected on its sampling axis, in pixels.
double expected_points(const TriangleMesh& m, float pixel) {
  double sum = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const int a = sampling_axis(m, t);
    if (a < 0) continue;
    const Vec3f p = m.positions[m.triangles[t][0]], q = m.positions[m.triangles[t][1]], r = m.positions[m.triangles[t][2]];
    sum += 0.5 * std::fabs(double(cross(q - p, r - p)[a]));
  }
  return sum / (double(pixel) * pixel);
}

// Pixels with an odd number of layers (a closed surface is entered and left: always even).
std::size_t odd_pixels(const std::array<AxisLayers, 3>& layers) {
  std::size_t odd = 0;
  for (const AxisLayers& L : layers)
    for (std::size_t p = 0; p + 1 < L.offsets.size(); ++p) odd += (L.offsets[p + 1] - L.offsets[p]) % 2;
  return odd;
}

// Fragments (axis, pixel, layer, triangle) found by one backend and not the other, over all found.
double layer_mismatch(const std::array<AxisLayers, 3>& a, const std::array<AxisLayers, 3>& b, std::size_t* differing = nullptr) {
  std::size_t diff = 0, total = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const AxisLayers &A = a[static_cast<std::size_t>(axis)], &B = b[static_cast<std::size_t>(axis)];
    for (std::size_t p = 0; p + 1 < A.offsets.size(); ++p) {
      std::vector<std::uint32_t> x(A.triangles.begin() + A.offsets[p], A.triangles.begin() + A.offsets[p + 1]);
      std::vector<std::uint32_t> y(B.triangles.begin() + B.offsets[p], B.triangles.begin() + B.offsets[p + 1]);
      total += std::max(x.size(), y.size());
      if (x != y) diff += std::max(x.size(), y.size());
    }
  }
  if (differing) *differing = diff;
  return total ? double(diff) / double(total) : 0.0;
}

// Points of `a` with no point of `b` at the same pixel centre and depth (within 1e-3 pixel): a
// point's two image coordinates are the same floats in both backends, only its depth may differ.
std::size_t unmatched_points(const PointSet& a, const PointSet& b, float pixel) {
  std::multimap<std::tuple<int, float, float>, float> index;
  for (Vec3f q : b.positions)
    for (int axis = 0; axis < 3; ++axis) index.insert({{axis, q[(axis + 1) % 3], q[(axis + 2) % 3]}, q[axis]});
  std::size_t missing = 0;
  for (Vec3f q : a.positions) {
    bool found = false;
    for (int axis = 0; axis < 3 && !found; ++axis) {
      auto range = index.equal_range({axis, q[(axis + 1) % 3], q[(axis + 2) % 3]});
      for (auto it = range.first; it != range.second && !found; ++it) found = std::fabs(it->second - q[axis]) <= 1e-3f * pixel;
    }
    missing += !found;
  }
  return missing;
}

TEST(Sample, CountsMatchProjectedAreaOnAnalyticMeshes) {
  for (const char* shape : {"octahedron", "cube", "sphere"}) {
    const TriangleMesh m = generate_mesh(shape, 12);
    for (const char* backend : {"cpu", "gl"}) {
      SampleStats st;
      const PointSet p = sample_mesh(m, options(backend), shape, &st);
      const double expected = expected_points(m, st.pixel);
      EXPECT_NEAR(double(p.size()) / expected, 1.0, 0.02) << shape << " " << backend << ": " << p.size() << " vs " << expected;
      EXPECT_EQ(st.backend, backend);
      ASSERT_EQ(p.normals.size(), p.size());
      ASSERT_EQ(p.radii.size(), p.size());
      ASSERT_EQ(p.colors.size(), p.size());
    }
  }
}

TEST(Sample, PointsLieOnTheSurface) {
  // Exactly on the flat faces; on the sphere mesh within its chord error.
  for (const char* backend : {"cpu", "gl"}) {
    const PointSet oct = sample_mesh(generate_mesh("octahedron", 8), options(backend), "oct");
    double worst = 0;
    for (Vec3f q : oct.positions) worst = std::max(worst, std::fabs(std::fabs(q.x) + std::fabs(q.y) + std::fabs(q.z) - 1.0));
    EXPECT_LT(worst, 2e-6) << backend;
    const PointSet cube = sample_mesh(generate_mesh("cube", 4), options(backend), "cube");
    worst = 0;
    for (Vec3f q : cube.positions) {
      const double m = std::max({std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
      worst = std::max(worst, std::fabs(m - 1.0));
    }
    EXPECT_LT(worst, 2e-6) << backend;
    const TriangleMesh sm = generate_mesh("sphere", 16);
    const PointSet sphere = sample_mesh(sm, options(backend), "sphere");
    // No point of the inscribed mesh is nearer the centre than the nearest triangle plane.
    double inner = 1;
    for (const Triangle& t : sm.triangles) {
      const Vec3f a = sm.positions[t[0]], n = normalized(cross(sm.positions[t[1]] - a, sm.positions[t[2]] - a));
      inner = std::min(inner, double(std::fabs(dot(n, a))));
    }
    for (std::size_t i = 0; i < sphere.size(); ++i) {
      const double r = length(sphere.positions[i]);
      ASSERT_LE(r, 1 + 1e-6) << backend;
      ASSERT_GE(r, inner - 1e-6) << backend;
      ASSERT_GT(dot(sphere.normals[i], sphere.positions[i]), 0.9f) << backend << ": outward normals";
    }
  }
}

TEST(Sample, ClosedMeshesHaveEvenLayerCounts) {
  for (const char* shape : {"octahedron", "cube", "sphere"}) {
    const TriangleMesh m = generate_mesh(shape, 10);
    const SampleGrid g = sample_grid(m, 157);  // an odd size: pixel centres off the symmetry planes
    SampleOptions all;  // every triangle on every axis: each pixel sees the whole closed surface
    all.per_axis_triangles = false;
    EXPECT_EQ(odd_pixels(peel_layers_cpu(m, g, all)), 0u) << shape << " cpu";
    EXPECT_EQ(odd_pixels(peel_layers_gl(m, g, all)), 0u) << shape << " gl";
  }
}

TEST(Sample, GlMatchesTheCpuReference) {
  for (const char* shape : {"octahedron", "cube", "sphere"}) {
    const TriangleMesh m = generate_mesh(shape, 10);
    const SampleGrid g = sample_grid(m, 157);
    const auto cpu = peel_layers_cpu(m, g, {}), gl = peel_layers_gl(m, g, {});
    for (int a = 0; a < 3; ++a) EXPECT_EQ(cpu[static_cast<std::size_t>(a)].layers, gl[static_cast<std::size_t>(a)].layers);
    // Only pixel centres within GL's 1/256-pixel vertex snapping of an edge may differ.
    EXPECT_LT(layer_mismatch(cpu, gl), 0.002) << shape;
  }
}

TEST(Sample, PerAxisTrianglesGiveTheSamePointsWithFewerLayers) {
  const TriangleMesh m = generate_mesh("sphere", 12);
  SampleOptions all = options("cpu"), per_axis = options("cpu");
  all.per_axis_triangles = false;
  SampleStats sa, sp;
  const PointSet a = sample_mesh(m, all, "sphere", &sa), p = sample_mesh(m, per_axis, "sphere", &sp);
  ASSERT_EQ(a.size(), p.size());
  EXPECT_TRUE(a.positions == p.positions);
  EXPECT_LT(sp.fragments, sa.fragments * 6 / 10);  // the sphere: 55%
  SampleStats gp;
  per_axis.backend = "gl";
  const PointSet g = sample_mesh(m, per_axis, "sphere", &gp);
  EXPECT_NEAR(double(g.size()), double(p.size()), 0.001 * double(p.size()));
}

TEST(Sample, DensityIsContinuousAcrossAxisSetBorders) {
  // Points near a border (two normal components within 2% of the largest) on either side have
  // the same nearest-neighbour spacing: sampling switches axis where both axes see the patch alike.
  const PointSet p = sample_mesh(generate_mesh("sphere", 24), options("cpu", 300), "sphere");
  const Neighborhoods nb = k_nearest(p.positions, 1);
  double side[3] = {0, 0, 0};
  std::size_t count[3] = {0, 0, 0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3f q = p.positions[i];
    const float ax[3] = {std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)};
    const int a = static_cast<int>(std::max_element(ax, ax + 3) - ax);
    float second = 0;
    for (int k = 0; k < 3; ++k)
      if (k != a) second = std::max(second, ax[k]);
    if (ax[a] - second > 0.02f * ax[a] || ax[a] > 0.9f) continue;  // not near a border (nor a pole)
    side[a] += double(nb.distances[nb.offsets[i]]);
    ++count[a];
  }
  for (int a = 0; a < 3; ++a) ASSERT_GT(count[a], 100u);
  const double m0 = side[0] / count[0], m1 = side[1] / count[1], m2 = side[2] / count[2];
  EXPECT_NEAR(m0 / m1, 1.0, 0.05);
  EXPECT_NEAR(m1 / m2, 1.0, 0.05);
}

TEST(Sample, GlIsDeterministic) {
  const TriangleMesh m = generate_mesh("sphere", 12);
  const PointSet a = sample_mesh(m, options("gl"), "s"), b = sample_mesh(m, options("gl"), "s");
  EXPECT_TRUE(a.positions == b.positions);
}

// The cube [-1, 1]^3 with the cube [-0.5, 0.5]^3 inside it (its triangles after the outer's).
TriangleMesh nested_cubes() {
  TriangleMesh m = generate_mesh("cube", 6);
  const TriangleMesh inner = generate_mesh("cube", 6);
  const std::uint32_t base = static_cast<std::uint32_t>(m.positions.size());
  for (const Vec3f& p : inner.positions) m.positions.push_back(p * 0.5f);
  for (const Triangle& t : inner.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  m.colors.clear(), m.normals.clear();
  return m;
}

// A cube inside a larger cube: no outside view sees the inner one, so its points are dropped
// (issue 31: an assembly's inner parts colour nothing); with visibility off they stay. Every kept
// point lies on the triangle it is said to come from.
TEST(Sample, SurfacesNoOutsideViewSeesAreDropped) {
  TriangleMesh m = nested_cubes();
  const auto inside = [](const PointSet& p) {
    std::size_t n = 0;
    for (const Vec3f& x : p.positions) n += std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)}) < 0.75f;
    return n;
  };
  SampleOptions all = options("cpu", 120);
  all.visibility.views = 0;
  SampleStats st_all, st;
  const PointSet every = sample_mesh(m, all, "nested", &st_all);
  std::vector<std::uint32_t> triangles;
  const PointSet seen = sample_mesh(m, options("cpu", 120), "nested", &st, &triangles);
  EXPECT_GT(inside(every), every.size() / 6);  // the inner cube, a quarter of the area
  EXPECT_EQ(inside(seen), 0u);
  EXPECT_EQ(st_all.hidden, 0u);
  EXPECT_EQ(st.hidden, every.size() - seen.size());
  EXPECT_NEAR(double(seen.size()) / double(every.size() - inside(every)), 1.0, 1e-9);  // the outer cube whole
  ASSERT_EQ(triangles.size(), seen.size());
  for (std::size_t i = 0; i < seen.size(); ++i) {
    const Triangle& t = m.triangles[triangles[i]];
    const Vec3f a = m.positions[t[0]], n = normalized(cross(m.positions[t[1]] - a, m.positions[t[2]] - a));
    ASSERT_LT(std::fabs(dot(seen.positions[i] - a, n)), 1e-5f) << i;
  }
}

// A MASK material (leaves, cut-out cards) occludes nothing: what lies behind its cut-outs is seen.
TEST(Sample, MaskedSurfacesHideNothing) {
  TriangleMesh m = nested_cubes();
  SurfaceMaterial card;
  card.alpha_mode = AlphaMode::kMask;  // no texture: nothing is cut out, yet it may be
  m.materials = {SurfaceMaterial{}, card};
  m.triangle_materials.assign(m.triangles.size(), 0);
  for (std::size_t t = 0; t < m.triangles.size() / 2; ++t) m.triangle_materials[t] = 1;  // the outer cube is the card
  SampleStats st;
  sample_mesh(m, options("cpu", 120), "cards", &st);
  EXPECT_EQ(st.hidden, 0u);
}

TEST(Sample, BadMeshesGetClearErrors) {
  TriangleMesh m = generate_mesh("cube", 1);
  auto code = [](const TriangleMesh& mesh) {
    try {
      sample_mesh(mesh, options("cpu"), "bad.off");
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.off"), std::string::npos);
      return e.code();
    }
    return std::string("no error");
  };
  TriangleMesh empty = m;
  empty.triangles.clear();
  EXPECT_EQ(code(empty), "mesh.no_triangles");
  TriangleMesh index = m;
  index.triangles[3][1] = 999;
  EXPECT_EQ(code(index), "mesh.bad_index");
  TriangleMesh nan = m;
  nan.positions[2].y = NAN;
  EXPECT_EQ(code(nan), "mesh.nonfinite");
  TriangleMesh flat = m;
  for (Vec3f& p : flat.positions) p = {0, 0, 0};
  EXPECT_EQ(code(flat), "mesh.no_points");
}

// Real meshes (scripts/fetch-models.sh): GL against the CPU, the share of differing fragments.
TEST(SampleModels, GlMatchesCpuOnCgalMeshes) {
  const char* env = std::getenv("QF_MODELS");
  const std::string dir = env ? env : std::string(std::getenv("HOME") ? std::getenv("HOME") : "") + "/.cache/quasiflat/models";
  if (!std::filesystem::exists(dir + "/bunny00.off")) GTEST_SKIP() << "models not fetched (scripts/fetch-models.sh)";
  for (const char* name : {"bunny00.off", "elephant.off", "fandisk.off"}) {
    const TriangleMesh m = read_model(dir + "/" + name).mesh;
    const SampleGrid g = sample_grid(m, 400);
    const auto cpu = peel_layers_cpu(m, g, {}), gl = peel_layers_gl(m, g, {});
    std::size_t differing = 0;
    const double share = layer_mismatch(cpu, gl, &differing);
    const PointSet pc = points_from_layers(m, g, cpu), pg = points_from_layers(m, g, gl);
    const std::size_t only_cpu = unmatched_points(pc, pg, g.pixel), only_gl = unmatched_points(pg, pc, g.pixel);
    std::printf("%s at 400: %zu / %zu points (cpu / gl); %zu only on the CPU, %zu only on GL (%.4f%%); "
                "fragments in pixels whose layers differ: %.3f%%\n",
                name, pc.size(), pg.size(), only_cpu, only_gl, 100.0 * double(only_cpu + only_gl) / double(pc.size()), 100 * share);
    // Edge ties pick the triangle on the other side of an edge: the same surface point, and the
    // same point unless the two triangles are sampled on different axes.
    EXPECT_LT(double(only_cpu + only_gl), 0.001 * double(pc.size())) << name;
    EXPECT_LT(share, 0.01) << name;
  }
}

// linear_to_srgb8's tables give the formula's byte exactly: at and around every byte boundary (by
// ulps, and by the margin where the tables hand over to the formula), at random, and at the edges.
TEST(SurfaceColor, TabledSrgbEncodingIsTheFormulaBitForBit) {
  const detail::SrgbTables& t = detail::srgb_tables();
  std::vector<double> probes{0.0, -0.0, 1.0, -1e-300, 1e-300, 4.9e-324, 0.0031308, 0.5, 1 - 1e-17, 1 + 1e-16, -INFINITY, INFINITY, NAN};
  for (int k = 1; k < 256; ++k) {
    const double b = t.thresholds[static_cast<std::size_t>(k)];
    ASSERT_EQ(linear_to_srgb8_formula(b), k);
    ASSERT_EQ(linear_to_srgb8_formula(std::nextafter(b, 0.0)), k - 1);
    for (double d : {detail::SrgbTables::kMargin, -detail::SrgbTables::kMargin}) {
      double p = b + d;
      for (int u = 0; u < 4; ++u) probes.push_back(p = std::nextafter(p, 2.0)), probes.push_back(b + d - u * 1e-17);
    }
    double up = b, down = b;
    for (int u = 0; u < 40; ++u) probes.push_back(up = std::nextafter(up, 2.0)), probes.push_back(down = std::nextafter(down, -1.0));
  }
  for (int i = 0; i <= detail::SrgbTables::kBuckets; ++i) probes.push_back(double(i) / detail::SrgbTables::kBuckets);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> any(-0.1, 1.1);
  for (int i = 0; i < 2000000; ++i) probes.push_back(any(rng));
  for (double p : probes) ASSERT_EQ(int(linear_to_srgb8(p)), int(linear_to_srgb8_formula(p))) << "l = " << p;
}

// sample_texture against a plain bilinear lookup with every wrap mode, inside and outside 0..1,
// exactly (the sampled colours of every textured asset depend on it).
TEST(SurfaceColor, TextureLookupIsPlainBilinearWithEveryWrap) {
  TextureImage img{5, 3, {}};
  for (int i = 0; i < 5 * 3 * 4; ++i) img.rgba.push_back(static_cast<std::uint8_t>(i * 37 % 256));
  const auto wrap = [](int i, int n, TextureWrap m) {
    if (m == TextureWrap::kClampToEdge) return std::clamp(i, 0, n - 1);
    if (m == TextureWrap::kMirroredRepeat) {
      const int r = ((i % (2 * n)) + 2 * n) % (2 * n);
      return r < n ? r : 2 * n - 1 - r;
    }
    return ((i % n) + n) % n;
  };
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coord(-2.5, 3.5);
  const TextureWrap modes[3] = {TextureWrap::kRepeat, TextureWrap::kClampToEdge, TextureWrap::kMirroredRepeat};
  for (int i = 0; i < 30000; ++i) {
    // Random, then texel centres and edges, signed zeros, integers and huge coordinates.
    const float special[] = {-0.0f, 0.0f, 1.0f, -1.0f, 0.1f, 0.9f, 2.0f, -3.0f, 1e8f, -1e8f, 1e30f, -1e30f};
    const Vec2f uv{i < 144 ? special[i % 12] : static_cast<float>(coord(rng)),
                   i < 144 ? special[i / 12] : static_cast<float>(i % 7 == 0 ? 0.5 : coord(rng))};
    const TextureWrap ws = modes[i % 3], wt = modes[(i / 3) % 3];
    const double fu = ws == TextureWrap::kRepeat ? uv.x - std::floor(uv.x) : uv.x;
    const double fv = wt == TextureWrap::kRepeat ? uv.y - std::floor(uv.y) : uv.y;
    const double x = fu * img.width - 0.5, y = fv * img.height - 0.5, x0 = std::floor(x), y0 = std::floor(y);
    std::array<float, 4> want{0, 0, 0, 0};
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const double w = (dx ? x - x0 : 1 - (x - x0)) * (dy ? y - y0 : 1 - (y - y0));
        if (w == 0) continue;
        const int cx = int(std::fmax(std::fmin(x0, 1e9), -1e9)), cy = int(std::fmax(std::fmin(y0, 1e9), -1e9));
        const std::uint8_t* p = &img.rgba[static_cast<std::size_t>(wrap(cy + dy, img.height, wt) * img.width + wrap(cx + dx, img.width, ws)) * 4];
        for (int c = 0; c < 3; ++c) want[static_cast<std::size_t>(c)] += static_cast<float>(w * srgb8_to_linear(p[c]));
        want[3] += static_cast<float>(w * p[3] / 255.0);
      }
    ASSERT_EQ(sample_texture(img, uv, ws, wt), want) << uv.x << " " << uv.y;
  }
}

}  // namespace
}  // namespace qf
