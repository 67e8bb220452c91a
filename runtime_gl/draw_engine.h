// The engine method: an EngineScene drawn as a standard glTF PBR engine draws it (three.js r187's
// MeshStandardMaterial is the model followed, formula by formula): base colour factor x sRGB base
// colour texture x COLOR_0, metallic and roughness factors x the metallic-roughness texture (B, G),
// occlusion (R) of the ambient light, emission (factor x sRGB texture), alpha MASK / BLEND, the normal map in the file's tangent frame (or
// the UV-derivative frame without TANGENT), flat normals without NORMAL, back faces culled unless
// the material is double-sided (then lit with the flipped normal), GGX specular with Smith
// visibility and multiple-scattering compensation, Lambert diffuse reduced by Fresnel, lighting in
// linear light, sRGB output, no tone mapping; lines and points unlit, one pixel wide.
//
// The only runtime code past GL 1.1: per-texel normals and linear-space lighting need shaders
// (GLSL 1.30). Needs a current context (egl_context.h); draws into the bound framebuffer.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "runtime_gl/camera.h"
#include "runtime_gl/engine_scene.h"

namespace qf::render {

class EngineDrawer {
 public:
  EngineDrawer();  // compiles the program and builds the DFG table
  ~EngineDrawer();
  EngineDrawer(const EngineDrawer&) = delete;
  EngineDrawer& operator=(const EngineDrawer&) = delete;

  // Uploads the scene's textures (with mipmaps); the scene must outlive the drawer's use of it.
  void set_scene(const EngineScene& scene);
  // Draws the scene over what the framebuffer holds (clear it first): opaque and masked
  // primitives in file order, then blended ones in file order with depth writes off.
  // `alpha_mode` ("OPAQUE", "MASK", "BLEND") and `alpha_cutoff` (>= 0) override every triangle
  // material's, to measure what another choice would look like. `mipmaps` false samples the
  // colour and normal textures' base level alone (bilinear). Returns the primitives drawn.
  std::size_t draw(const Camera& camera, const EngineLights& lights, const std::optional<std::string>& alpha_mode = {},
            float alpha_cutoff = -1, bool mipmaps = true);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The split-sum table of the GGX BRDF (Karis 2013) that the engine's multiple-scattering terms
// read: for roughness (i + 0.5) / n and N.V = (j + 0.5) / n, the scale and bias of F0 in the
// directional albedo, (scale, bias) at [2 (j n + i)]. Computed by importance sampling with
// height-correlated Smith visibility, as three.js's built-in 16 x 16 table is.
std::vector<float> dfg_table(int n, int samples);

}  // namespace qf::render
