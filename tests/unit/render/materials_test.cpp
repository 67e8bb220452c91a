// Materials as the engine shows them (issue 31, item 3): a glTF asset's metallic, roughness and
// emissive channels read, painted onto the quads, kept as factors where constant and as ORM and
// emissive textures where they vary, and drawn so by the engine method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include <unistd.h>

#include "core/file_io.h"
#include "gl/egl.h"
#include "gltf/glb.h"
#include "io/model_io.h"
#include "pipeline/asset.h"
#include "runtime_gl/camera.h"
#include "runtime_gl/draw_gl11.h"
#include "runtime_gl/loader.h"
#include "shapes/plate.h"
#include "measure/reference_scene.h"

namespace qf::render {
namespace {

namespace fs = std::filesystem;

// This process's folder for the fixtures, removed when the process ends (each test runs in a
// process of its own under ctest).
const fs::path& fixture_folder() {
  struct Folder {
    fs::path dir = fs::temp_directory_path() / ("qf_materials_" + std::to_string(::getpid()));
    ~Folder() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  };
  static const Folder folder;
  return folder.dir;
}

// The fixture written as a glTF asset in the process's folder; returns its path.
std::string write_plate(bool varying, const std::string& name, bool occluded = false) {
  fs::create_directories(fixture_folder());
  const std::string path = (fixture_folder() / (name + ".glb")).string();
  write_bytes_atomically(path, encode_textured_mesh_glb(generate_material_plate(varying, occluded)));
  return path;
}

// The bake's one impostor level (8 quads asked for) of the asset at `path`, as an engine loads it.
BakedScene baked_level(const std::string& path) {
  AssetOptions o;
  o.bake.primitives = {8};
  o.sample.ldi_size = 96;
  o.cheap_triangles = 0;  // a plate of a few triangles is cheap: baked all the same
  o.mesh_lods = AssetOptions::MeshLods::kNone;
  const AssetBake b = bake_asset(path, o, path);
  for (const OutputFile& f : b.files)
    if (f.name.size() > 4 && f.name.substr(f.name.size() - 4) == ".glb") return load_baked(f.bytes, f.name);
  ADD_FAILURE() << "the bake wrote no level";
  return {};
}

TEST(Materials, TheGltfReaderKeepsMetallicRoughnessAndEmission) {
  const TriangleMesh m = read_model(write_plate(true, "read")).mesh;
  ASSERT_EQ(m.materials.size(), 2u);
  const SurfaceMaterial& left = m.materials[0];
  const SurfaceMaterial& right = m.materials[1];
  EXPECT_FLOAT_EQ(left.roughness, 0.9f);
  EXPECT_FLOAT_EQ(left.metallic, 0);
  EXPECT_LT(left.metallic_roughness.image, 0);
  EXPECT_EQ(left.emissive, (std::array<float, 3>{0, 0, 0}));
  EXPECT_FLOAT_EQ(right.roughness, 1);
  EXPECT_FLOAT_EQ(right.metallic, 1);
  ASSERT_GE(right.metallic_roughness.image, 0);
  EXPECT_EQ(m.textures[static_cast<std::size_t>(right.metallic_roughness.image)].rgba[1], 51);  // G: roughness
  EXPECT_EQ(right.emissive, (std::array<float, 3>{1, 0.5f, 0}));
  EXPECT_GE(right.emissive_texture.image, 0);
  EXPECT_LT(right.occlusion.image, 0);
  EXPECT_TRUE(m.has_material_channels());
}

TEST(Materials, ConstantChannelsBecomeFactorsWithoutTextures) {
  const BakedScene level = baked_level(write_plate(false, "constant"));
  ASSERT_FALSE(level.engine.primitives.empty());
  for (const EnginePrimitive& p : level.engine.primitives) {
    EXPECT_FLOAT_EQ(p.material.roughness, 0.5f);
    EXPECT_FLOAT_EQ(p.material.metallic, 0);
    EXPECT_LT(p.material.metal_rough_texture, 0);
    EXPECT_LT(p.material.occlusion_texture, 0);
    EXPECT_LT(p.material.emissive_texture, 0);
    EXPECT_EQ(p.material.emissive, (std::array<float, 3>{0, 0, 0}));
  }
  EXPECT_EQ(level.engine.images.size(), 2u) << "colour and normal atlas only";
}

// Every covered texel of every quad's tile, with the point of the quad it stands for: calls
// f(x of that point, texel index into the atlas images, texel size in model units).
template <class F>
void for_each_covered_texel(const EnginePrimitive& p, const Image& color, F f) {
  for (std::size_t q = 0; q + 3 < p.positions.size() / 3; q += 4) {
    // Corners (-u,-v), (+u,-v), (+u,+v), (-u,+v) with uvs (u0,v1), (u1,v1), (u1,v0), (u0,v0).
    const auto pos = [&](std::size_t c, int k) { return p.positions[3 * (q + c) + static_cast<std::size_t>(k)]; };
    const float u0 = p.uvs[2 * q], v1 = p.uvs[2 * q + 1], u1 = p.uvs[2 * (q + 2)], v0 = p.uvs[2 * (q + 2) + 1];
    const int x0 = static_cast<int>(std::lround(u0 * color.width)), x1 = static_cast<int>(std::lround(u1 * color.width));
    const int y0 = static_cast<int>(std::lround(v0 * color.height)), y1 = static_cast<int>(std::lround(v1 * color.height));
    const double side = std::hypot(pos(1, 0) - pos(0, 0), pos(1, 1) - pos(0, 1)) / std::max(1, x1 - x0);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(color.width) + static_cast<std::size_t>(x);
        if (color.rgba[4 * k + 3] == 0) continue;
        const double s = (x + 0.5 - x0) / (x1 - x0), t = (y1 - (y + 0.5)) / (y1 - y0);
        f(pos(0, 0) + s * (pos(1, 0) - pos(0, 0)) + t * (pos(3, 0) - pos(0, 0)), k, side);
      }
  }
}

TEST(Materials, VaryingChannelsBecomeOrmAndEmissiveTexturesOnTheRightQuads) {
  const BakedScene level = baked_level(write_plate(true, "varying"));
  ASSERT_EQ(level.engine.primitives.size(), 1u);
  const EnginePrimitive& p = level.engine.primitives[0];
  const EngineMaterial& mat = p.material;
  ASSERT_GE(mat.metal_rough_texture, 0);
  ASSERT_GE(mat.emissive_texture, 0);
  EXPECT_LT(mat.occlusion_texture, 0) << "no occlusion in the input: none in the level";
  EXPECT_FLOAT_EQ(mat.roughness, 1);
  EXPECT_FLOAT_EQ(mat.metallic, 1);
  // Emission varies in R and G; B is 0 everywhere: a factor, its texels 255 (factor x texel = 0).
  EXPECT_EQ(mat.emissive, (std::array<float, 3>{1, 1, 0}));
  const Image& color = level.engine.images[static_cast<std::size_t>(mat.base_texture)];
  const Image& orm = level.engine.images[static_cast<std::size_t>(mat.metal_rough_texture)];
  const Image& emissive = level.engine.images[static_cast<std::size_t>(mat.emissive_texture)];
  std::size_t left = 0, right = 0;
  for_each_covered_texel(p, color, [&](double x, std::size_t k, double texel) {
    if (std::fabs(x - 1) < 0.05 + 2 * texel) return;  // texels that mix the halves
    const std::uint8_t* o = &orm.rgba[4 * k];
    const std::uint8_t* e = &emissive.rgba[4 * k];
    const auto near = [](int v, int want) { return std::abs(v - want) <= 2; };
    if (x < 1) {
      ++left;
      EXPECT_TRUE(near(o[1], 230) && near(o[2], 0)) << "left: roughness 0.9, metallic 0 at x " << x;
      EXPECT_TRUE(near(e[0], 0) && near(e[1], 0)) << "left: no emission at x " << x;
    } else {
      ++right;
      EXPECT_TRUE(near(o[1], 51) && near(o[2], 255)) << "right: roughness 0.2, metallic 1 at x " << x;
      EXPECT_TRUE(near(e[0], 255) && near(e[1], 188)) << "right: emission (1, 0.5) as sRGB at x " << x;
    }
    EXPECT_EQ(e[2], 255) << "constant channel: the factor carries it";
    EXPECT_EQ(o[0], 255) << "occlusion 1";
  });
  EXPECT_GT(left, 50u);
  EXPECT_GT(right, 50u);
}

// Occlusion has no factor in glTF: where it varies, the ORM image's R carries it (1 where the
// asset has none) and the level's occlusionTexture is that same image.
TEST(Materials, VaryingOcclusionSharesTheOrmImage) {
  const BakedScene level = baked_level(write_plate(false, "occluded", true));
  ASSERT_EQ(level.engine.primitives.size(), 1u);
  const EnginePrimitive& p = level.engine.primitives[0];
  const EngineMaterial& mat = p.material;
  ASSERT_GE(mat.occlusion_texture, 0);
  EXPECT_EQ(mat.occlusion_texture, mat.metal_rough_texture);
  EXPECT_FLOAT_EQ(mat.roughness, 0.5f) << "roughness stays a factor";
  EXPECT_LT(mat.emissive_texture, 0);
  const Image& color = level.engine.images[static_cast<std::size_t>(mat.base_texture)];
  const Image& orm = level.engine.images[static_cast<std::size_t>(mat.occlusion_texture)];
  std::size_t left = 0, right = 0;
  for_each_covered_texel(p, color, [&](double x, std::size_t k, double texel) {
    if (std::fabs(x - 1) < 0.05 + 2 * texel) return;
    const int r = orm.rgba[4 * k], want = x < 1 ? 255 : 128;
    (x < 1 ? left : right) += 1;
    EXPECT_LE(std::abs(r - want), 2) << "occlusion at x " << x;
    EXPECT_EQ(orm.rgba[4 * k + 1], 255) << "constant roughness: its factor carries it";
  });
  EXPECT_GT(left, 50u);
  EXPECT_GT(right, 50u);
}

// In the dark (no lights), only emission shows: the level's emitting quads light up where the
// asset's emitting half does, and its other half stays black.
TEST(Materials, TheEngineMethodDrawsEmissionInTheDark) {
  const std::string path = write_plate(true, "dark");
  const BakedScene level = baked_level(path);
  const TriangleMesh mesh = read_model(path).mesh;
  const MeshScene ms = mesh_scene(mesh, path);
  const EngineScene reference = engine_scene(mesh, ms);
  HeadlessContext context;
  const int size = 96;
  Renderer r(size, size);
  DrawSettings s;
  s.method = Method::kEngine;
  s.lights.directional = 0;
  s.lights.ambient = 0;
  const Camera c = orbit_camera(bounding_sphere(reference.bounds), orbit_direction(0, 60), 0, size, size);
  auto render = [&](const EngineScene& scene) {
    r.set_engine_scene(scene);
    r.draw(c, s);
    return r.read_pixels();
  };
  const Image ref = render(reference), baked = render(level.engine);
  std::size_t ref_bright = 0, both = 0, baked_bright = 0;
  for (std::size_t k = 0; k < ref.rgba.size(); k += 4) {
    const bool a = ref.rgba[k] > 128, b = baked.rgba[k] > 128;
    ref_bright += a, baked_bright += b, both += a && b;
  }
  EXPECT_GT(ref_bright, static_cast<std::size_t>(size * size / 20)) << "the asset's emitting half shows";
  EXPECT_GT(both, ref_bright * 85 / 100) << "the level emits where the asset does";
  EXPECT_GT(both, baked_bright * 85 / 100) << "and not where it does not";
}

}  // namespace
}  // namespace qf::render
