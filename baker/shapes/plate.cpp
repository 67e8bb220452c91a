// The material plate (plate.h): two materials on a flat grid, written out as plain data.
#include "shapes/plate.h"

namespace qf {
namespace {

// A 2 x 2 image of one RGBA texel value.
TextureImage flat_image(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  TextureImage t;
  t.width = t.height = 2;
  for (int k = 0; k < 4; ++k) t.rgba.insert(t.rgba.end(), {r, g, b, 255});
  return t;
}

}  // namespace

TriangleMesh generate_material_plate(bool varying, bool occluded) {
  TriangleMesh m;
  constexpr int kCols = 16, kRows = 8;
  for (int j = 0; j <= kRows; ++j)
    for (int i = 0; i <= kCols; ++i) {
      m.positions.push_back({2.0f * i / kCols, 1.0f * j / kRows, 0});
      m.normals.push_back({0, 0, 1});
    }
  SurfaceMaterial left, right;
  left.name = "left", right.name = "right";
  left.base_color = {0.8f, 0.3f, 0.2f, 1};
  right.base_color = {0.3f, 0.6f, 0.9f, 1};
  left.double_sided = right.double_sided = true;  // seen from any side, as a sample should be
  right.metallic_roughness.image = 0;
  if (varying) {
    left.roughness = 0.9f, left.metallic = 0;
    right.roughness = 1, right.metallic = 1;
    m.textures.push_back(flat_image(255, 51, 255));
    right.emissive = {1, 0.5f, 0};
    right.emissive_texture.image = 1;
    m.textures.push_back(flat_image(255, 255, 255));
  } else {
    left.roughness = right.roughness = 0.5f;
    left.metallic = right.metallic = 0;
    m.textures.push_back(flat_image(255, 255, 255));
  }
  if (occluded) {
    right.occlusion.image = static_cast<int>(m.textures.size());
    m.textures.push_back(flat_image(128, 255, 255));
  }
  m.materials = {left, right};
  const auto at = [](int i, int j) { return static_cast<std::uint32_t>(j * (kCols + 1) + i); };
  const auto uv = [](int i, int j) { return Vec2f{static_cast<float>(i) / kCols, static_cast<float>(j) / kRows}; };
  for (int j = 0; j < kRows; ++j)
    for (int i = 0; i < kCols; ++i) {
      const std::uint32_t material = i < kCols / 2 ? 0 : 1;
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.corner_uvs.push_back({uv(i, j), uv(i + 1, j), uv(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      m.corner_uvs.push_back({uv(i, j), uv(i + 1, j + 1), uv(i, j + 1)});
      m.triangle_materials.insert(m.triangle_materials.end(), {material, material});
    }
  return m;
}

}  // namespace qf
