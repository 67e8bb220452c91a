// Mesh LODs by edge collapse (baker/simplify): a textured mesh keeps its materials and texture
// coordinates, and its textures can be halved for small screens.
#include <gtest/gtest.h>

#include <cmath>

#include "core/color.h"
#include "simplify/simplify.h"

namespace qf {
namespace {

// A bumpy n x n grid over [0,1]^2 (z varies, so collapses have a cost), UV = (x, y) at every
// corner; with `split`, the triangles left of x = 0.5 have material 0 and the others material 1.
TriangleMesh textured_grid(int n, bool split) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = float(i) / float(n), y = float(j) / float(n);
      m.positions.push_back({x, y, 0.05f * std::sin(7.0f * x) * std::cos(5.0f * y)});
    }
  const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (const Triangle& t : {Triangle{id(i, j), id(i + 1, j), id(i + 1, j + 1)}, Triangle{id(i, j), id(i + 1, j + 1), id(i, j + 1)}}) {
        m.triangles.push_back(t);
        std::array<Vec2f, 3> uv;
        for (std::size_t k = 0; k < 3; ++k) uv[k] = {m.positions[t[k]].x, m.positions[t[k]].y};
        m.corner_uvs.push_back(uv);
        m.triangle_materials.push_back(split && 2 * i + 1 > n ? 1u : 0u);
      }
  m.materials.resize(split ? 2 : 1);
  m.materials[0].texture = 0;
  m.textures.push_back({2, 2, std::vector<std::uint8_t>(16, 200)});
  return m;
}

TEST(Simplify, TexturedMeshKeepsItsTextureCoordinates) {
  const TriangleMesh in = textured_grid(24, false);
  const SimplifiedMesh s = simplify_mesh(in, in.triangles.size() / 8);
  ASSERT_LT(s.mesh.triangles.size(), in.triangles.size() / 4);
  ASSERT_EQ(s.mesh.corner_uvs.size(), s.mesh.triangles.size());
  ASSERT_EQ(s.mesh.triangle_materials.size(), s.mesh.triangles.size());
  EXPECT_EQ(s.mesh.materials.size(), 1u);
  EXPECT_EQ(s.mesh.textures.size(), 1u);
  // No seam here: every kept corner has the UV the input had at that position.
  for (std::size_t t = 0; t < s.mesh.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3f p = s.mesh.positions[s.mesh.triangles[t][k]];
      EXPECT_FLOAT_EQ(s.mesh.corner_uvs[t][k].x, p.x);
      EXPECT_FLOAT_EQ(s.mesh.corner_uvs[t][k].y, p.y);
    }
}

TEST(Simplify, TrianglesTakeTheMaterialOfTheirSide) {
  const TriangleMesh in = textured_grid(24, true);
  const SimplifiedMesh s = simplify_mesh(in, in.triangles.size() / 8);
  // Triangles well inside one half (centroid at least 0.2 from the border) have its material.
  std::size_t checked = 0;
  for (std::size_t t = 0; t < s.mesh.triangles.size(); ++t) {
    float x = 0;
    for (std::uint32_t v : s.mesh.triangles[t]) x += s.mesh.positions[v].x / 3;
    if (x > 0.3f && x < 0.7f) continue;
    EXPECT_EQ(s.mesh.triangle_materials[t], x <= 0.3f ? 0u : 1u) << "centroid x " << x;
    ++checked;
  }
  EXPECT_GT(checked, s.mesh.triangles.size() / 4);
}

// A texture seam stays a seam: the grid's right half samples another island of the texture (its
// UVs shifted by 10), so every kept triangle has its three corners' UVs in one island, and each
// corner the UV its position had on that side.
TEST(Simplify, TextureSeamsStaySeams) {
  TriangleMesh in = textured_grid(24, false);
  for (std::size_t t = 0; t < in.triangles.size(); ++t) {
    float x = 0;
    for (std::uint32_t v : in.triangles[t]) x += in.positions[v].x / 3;
    if (x > 0.5f)
      for (Vec2f& uv : in.corner_uvs[t]) uv.x += 10;
  }
  const SimplifiedMesh s = simplify_mesh(in, in.triangles.size() / 8);
  ASSERT_LT(s.mesh.triangles.size(), in.triangles.size() / 4);
  for (std::size_t t = 0; t < s.mesh.triangles.size(); ++t) {
    const bool right = s.mesh.corner_uvs[t][0].x >= 5;
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3f p = s.mesh.positions[s.mesh.triangles[t][k]];
      EXPECT_FLOAT_EQ(s.mesh.corner_uvs[t][k].x, p.x + (right ? 10.0f : 0.0f)) << "triangle " << t;
      EXPECT_FLOAT_EQ(s.mesh.corner_uvs[t][k].y, p.y);
    }
  }
}

TEST(Simplify, UntexturedMeshGetsNoSurfaceAttributes) {
  TriangleMesh in = textured_grid(16, false);
  in.corner_uvs.clear(), in.triangle_materials.clear(), in.materials.clear(), in.textures.clear();
  const SimplifiedMesh s = simplify_mesh(in, 64);
  EXPECT_LE(s.mesh.triangles.size(), 64u);
  EXPECT_TRUE(s.mesh.corner_uvs.empty() && s.mesh.triangle_materials.empty() && s.mesh.materials.empty());
}

// A flat-shaded cube: each face an n x n grid of its own vertices (split at the cube's edges, as a
// flat-shaded glTF's are) with the face's normal.
TriangleMesh flat_shaded_cube(int n) {
  TriangleMesh m;
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f}) {
      const auto at = [&](float u, float v) {
        float p[3];
        p[axis] = side, p[(axis + 1) % 3] = u, p[(axis + 2) % 3] = v;
        return Vec3f{p[0], p[1], p[2]};
      };
      Vec3f normal{0, 0, 0};
      (axis == 0 ? normal.x : axis == 1 ? normal.y : normal.z) = side;
      const auto first = static_cast<std::uint32_t>(m.positions.size());
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.positions.push_back(at(2.0f * i / n - 1, 2.0f * j / n - 1)), m.normals.push_back(normal);
      const auto id = [&](int i, int j) { return first + static_cast<std::uint32_t>(j * (n + 1) + i); };
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {  // wound outwards
          const bool flip = side < 0;
          m.triangles.push_back(flip ? Triangle{id(i, j), id(i + 1, j + 1), id(i + 1, j)} : Triangle{id(i, j), id(i + 1, j), id(i + 1, j + 1)});
          m.triangles.push_back(flip ? Triangle{id(i, j), id(i, j + 1), id(i + 1, j + 1)} : Triangle{id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    }
  return m;
}

// The input's normals follow their vertices, and vertices split at a crease stay split: every kept
// triangle of a flat-shaded cube has its face's normal at all three corners (hard edges stay hard).
TEST(Simplify, FlatShadedMeshKeepsItsHardEdges) {
  const TriangleMesh in = flat_shaded_cube(8);
  const SimplifiedMesh s = simplify_mesh(in, in.triangles.size() / 8);
  ASSERT_LT(s.mesh.triangles.size(), in.triangles.size() / 4);
  ASSERT_EQ(s.mesh.normals.size(), s.mesh.positions.size());
  std::size_t checked = 0;
  for (const Triangle& t : s.mesh.triangles) {
    const Vec3f a = s.mesh.positions[t[0]], b = s.mesh.positions[t[1]], c = s.mesh.positions[t[2]];
    const Vec3f e1{b.x - a.x, b.y - a.y, b.z - a.z}, e2{c.x - a.x, c.y - a.y, c.z - a.z};
    const Vec3f cross{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    // A triangle of no area along the cube's edges has no side to keep.
    if (cross.x == 0 && cross.y == 0 && cross.z == 0) continue;
    const Vec3f face = normalized(cross);
    for (std::uint32_t v : t) {
      const Vec3f n = s.mesh.normals[v];
      EXPECT_NEAR(n.x * face.x + n.y * face.y + n.z * face.z, 1.0, 1e-5) << "corner " << v;
    }
    ++checked;
  }
  EXPECT_GE(checked, 12u);  // at least two triangles a face
}

// simplifySloppy reaches a budget edge collapse cannot, and a budget above the mesh's own count
// (2P triangles of a thin lattice's impostor level) keeps the mesh instead of failing.
TEST(Simplify, SloppyMeetsTheBudgetAndLargeBudgetsKeepTheMesh) {
  const TriangleMesh in = textured_grid(16, false);
  for (SimplifyMethod method : {SimplifyMethod::kCollapse, SimplifyMethod::kSloppy}) {
    EXPECT_LE(simplify_mesh(in, 40, method).mesh.triangles.size(), 40u);
    EXPECT_EQ(simplify_mesh(in, 10 * in.triangles.size(), method).mesh.triangles.size(), in.triangles.size());
  }
}

TEST(Simplify, HalvedTextureAveragesInLinearLightWeightedByAlpha) {
  // Red and blue opaque over two transparent texels: half coverage, the colours' linear mean.
  TextureImage t{2, 2, {255, 0, 0, 255, 0, 0, 255, 255, 0, 255, 0, 0, 0, 255, 0, 0}};
  const TextureImage h = halve_texture(t);
  ASSERT_EQ(h.width, 1);
  ASSERT_EQ(h.height, 1);
  EXPECT_EQ(h.rgba[0], linear_to_srgb8(0.5));
  EXPECT_EQ(h.rgba[1], 0);  // the transparent texels' green does not show
  EXPECT_EQ(h.rgba[2], linear_to_srgb8(0.5));
  EXPECT_EQ(h.rgba[3], 128);
  // Odd sides round up; fit_textures halves until the longer side fits.
  TriangleMesh m;
  m.textures.push_back({5, 3, std::vector<std::uint8_t>(60, 255)});
  fit_textures(m, 2);
  EXPECT_EQ(m.textures[0].width, 2);
  EXPECT_EQ(m.textures[0].height, 1);
}

TEST(Simplify, MetallicRoughnessTexturesHalveAsDataNotColours) {
  // Roughness (G) 0 and 1 side by side: the halved texel is roughness 0.5 (byte 128), not the
  // sRGB mean (linear_to_srgb8(0.5) = 188), which would make the LOD rougher than the asset.
  TriangleMesh m;
  m.textures.push_back({2, 2, {0, 0, 0, 255, 0, 255, 0, 255, 0, 0, 0, 255, 0, 255, 0, 255}});
  m.textures.push_back(m.textures[0]);
  m.materials.resize(1);
  m.materials[0].metallic_roughness.image = 0;
  m.materials[0].texture = 1;  // the same texels as a base colour stay colours
  fit_textures(m, 1);
  EXPECT_EQ(m.textures[0].rgba[1], 128);
  EXPECT_EQ(m.textures[1].rgba[1], linear_to_srgb8(0.5));
}

}  // namespace
}  // namespace qf
