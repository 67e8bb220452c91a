// What a standard glTF engine sees of a file (three.js, Babylon, Godot, Unity's glTF importers):
// primitives in world space with their metallic-roughness materials, for the engine method
// (draw_engine.h). Any file qf-render reads becomes one: a baked .glb of any kind through the
// glTF loader, and the references (a mesh, a point set as disc splats, measure/reference_scene.h)
// as the engine would draw them had they been exported as glTF.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "runtime_gl/scene.h"

namespace qf::render {

// A glTF metallic-roughness material, with the spec's defaults (glTF 2.0, 5.19). A primitive
// without a material gets these defaults too, as engines do (white, fully metallic, rough).
struct EngineMaterial {
  std::array<float, 4> base_color{1, 1, 1, 1};  // linear RGBA factor
  int base_texture = -1;                        // index into EngineScene::images (sRGB), -1 none
  int base_wrap_s = 10497, base_wrap_t = 10497;  // its sampler's wraps (glTF codes = GL enums)
  // KHR_texture_transform, applied to the primitive's uvs when loading: u' = a u + b v + c, v' = d u + e v + f.
  std::array<float, 6> uv_transform{1, 0, 0, 0, 1, 0};
  float metallic = 1, roughness = 1;
  // The other channels' textures (linear, but emissive: sRGB), sampling the same uvs: B metallic
  // and G roughness (x the factors), R occlusion (of the ambient light: 1 + strength (R - 1)).
  int metal_rough_texture = -1, occlusion_texture = -1;
  int metal_rough_wrap_s = 10497, metal_rough_wrap_t = 10497, occlusion_wrap_s = 10497, occlusion_wrap_t = 10497;
  float occlusion_strength = 1;
  std::array<float, 3> emissive{0, 0, 0};  // linear RGB factor
  int emissive_texture = -1;               // sRGB, x the factor
  int emissive_wrap_s = 10497, emissive_wrap_t = 10497;
  int normal_texture = -1;                      // tangent-space normal map (linear), -1 none
  int normal_wrap_s = 10497, normal_wrap_t = 10497;
  float normal_scale = 1;
  enum class Alpha { kOpaque, kMask, kBlend } alpha = Alpha::kOpaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
};

// One primitive, already transformed to world space (node transforms composed; a mirroring
// transform has its triangles' winding swapped back so front faces stay front faces).
struct EnginePrimitive {
  enum class Mode { kTriangles, kLines, kPoints } mode = Mode::kTriangles;
  std::vector<float> positions;       // xyz per vertex
  std::vector<float> normals;         // xyz per vertex, or empty: flat shading (engines do that)
  std::vector<float> tangents;        // xyzw per vertex, or empty: frame from the UV derivatives
  std::vector<float> uvs;             // uv per vertex (the set the textures name), or empty
  std::vector<float> colors;          // COLOR_0 as linear RGBA per vertex, or empty (white)
  std::vector<std::uint32_t> indices; // never empty: non-indexed primitives get 0..n-1
  EngineMaterial material;
};

struct EngineScene {
  std::vector<EnginePrimitive> primitives;
  std::vector<Image> images;  // straight RGBA8 as stored in the file
  Bounds bounds;
};

// The lights of the engine method (and of the three.js harness, scripts/three-render): a white
// directional headlight of irradiance `directional` (three.js: DirectionalLight intensity, lux)
// from the eye towards the target, and ambient light of irradiance `ambient`. With pi x 0.7 and
// pi x 0.3 a white Lambertian surface facing the eye reflects 0.7 + 0.3 = 1 (before the Fresnel
// terms), as the fixed-function methods' headlight does.
struct EngineLights {
  float directional = 3.14159265f * 0.7f;
  float ambient = 3.14159265f * 0.3f;
};

}  // namespace qf::render
