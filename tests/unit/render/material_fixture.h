// A test asset with material channels (issue 31, item 3): a flat 2 x 1 plate in z = 0, facing +z,
// whose left half (x < 1) and right half are two materials. Written by the tests themselves
// (encode_textured_mesh_glb), so nothing is read from outside the repository.
#pragma once

#include <cstdint>
#include <vector>

#include "core/types.h"

namespace qf::test {

// A 2 x 2 image of one RGBA texel value.
inline TextureImage flat_image(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  TextureImage t;
  t.width = t.height = 2;
  for (int k = 0; k < 4; ++k) t.rgba.insert(t.rgba.end(), {r, g, b, 255});
  return t;
}

// `varying`: the left half a rough dielectric (roughness factor 0.9, metallic 0, no emission), the
// right half polished metal through its metallic-roughness texture (G 51 = roughness 0.2, B 255 =
// metallic 1, factors 1) and emitting (1, 0.5, 0): factor x a white emissive texture. Otherwise
// both halves have roughness 0.5 and metallic 0 (the right half through a texture of G 255, B 255
// under factors 0.5 and 0) and no emission: constant channels, which a level keeps as factors.
// `occluded`: the right half also has an occlusion texture of R 128 (occlusion 0.5).
inline TriangleMesh material_plate(bool varying, bool occluded = false) {
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

}  // namespace qf::test
