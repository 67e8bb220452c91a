// OpenGL 1.1 fixed-function drawing of impostor levels and reference scenes: the only runtime file
// with GL calls (plus the framebuffer object it renders into). Needs a current context
// (egl_context.h). Pixels are deterministic for a given Mesa build (gl-notes.md 4).
#pragma once

#include <memory>
#include <optional>

#include "runtime_gl/blend_order.h"
#include "runtime_gl/camera.h"
#include "runtime_gl/engine_scene.h"
#include "runtime_gl/scene.h"

namespace qf::render {

struct DrawSettings {
  Method method = Method::kOverlap;
  Rgb8 background{0, 0, 0};
  float alpha_ref = -1;        // lock-by-depth alpha test; < 0: the file's (extension alphaRef, 0.1)
  float transparency = 1;      // whole-object opacity a: the basis (alpha) is scaled by a (method.md 7)
  bool lighting = true;        // fixed-function headlight, one normal per quad / per splat / per vertex
  float depth_offset = 0;      // two-pass offset, world units; 0 = half the median quad half-diagonal
  std::optional<std::string> alpha_mode;  // engine method: override the material's alphaMode
  float alpha_cutoff = -1;     // engine method, MASK: < 0 = the material's alphaCutoff
  // Engine method: textures sampled through their mip levels (trilinear, as engines sample glTF
  // textures); false: the base level alone (bilinear). A level drawn both ways at a small size
  // shows what its mip levels cost in coverage (docs/textures.md, holes).
  bool mipmaps = true;
  // Overlap, two-pass and blend-all: where the summed basis functions cover a pixel by c >=
  // normalize, it shows their weighted mean colour, opaque; below, that colour at coverage
  // c / normalize. The basis sums to 1 on the surface only in theory: on curved parts not every
  // quad of a pixel's domains reaches it (see-through, holes), and where quads overlap in screen
  // space the plain sum saturates (bright streaks). 0 = off (the plain sum, as the paper draws);
  // < 0 = the method's default (kDefaultNormalize for overlap, off for the others).
  float normalize = -1;
  EngineLights lights;         // engine method
  // Engine method: the frame is cleared to alpha 0 instead of 1, so its alpha channel holds the
  // coverage (the method blends alpha as ONE, ONE_MINUS_SRC_ALPHA and writes 1 where opaque or
  // masked): one frame over black then gives the frame over any background (render_pair).
  bool coverage_alpha = false;
};

// The overlap method's normalising threshold: measured on bunny00 at 273 quads (26 views), holes
// 6.6% -> 1.7%, see-through 29% -> 3.7%, PSNR 20.7 -> 22.6 dB; 0.4 leaves fewer holes (1.1%) but
// widens silhouettes (IoU 0.942 -> 0.937).
constexpr float kDefaultNormalize = 0.5f;

// The threshold `s` asks for with its method (0 = no normalising composite).
float normalize_threshold(const DrawSettings& s);

struct DrawStats {
  std::size_t color_draws = 0, lock_draws = 0, other_draws = 0, state_changes = 0;
  std::size_t points = 0;      // point impostor: points drawn
  float points_weight = 0;     // point impostor: 1 = points only, 0 = mesh only, between = fading
};

class Renderer {
 public:
  // Renders into an off-screen framebuffer of width x height (RGBA8 + depth 24), or into the
  // current window's default framebuffer when `offscreen` is false.
  Renderer(int width, int height, bool offscreen = true);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The scene to draw (textures are uploaded here, with CPU-built mipmaps). The scene must outlive
  // the renderer's use of it.
  void set_scene(const ImpostorScene& scene);
  void set_scene(const SplatScene& scene);
  void set_scene(const MeshScene& scene);
  // A point impostor; with `mesh`, closer than the switch distance s Z0 it fades to the mesh
  // (from s Z0 down to 0.7 s Z0), so there is no popping.
  void set_scene(const PointImpostorScene& scene, const MeshScene* mesh = nullptr);
  // A vertex-clustering LOD: its triangles, thick lines thickness / R pixels wide (R = the model
  // size of a pixel at the line's distance) lit with the dynamic normal (V1 - C) x (V2 - C) x
  // (V2 - V1) of paper 3.3.2, and its points.
  void set_scene(const ClusterScene& scene);
  // What Method::kEngine draws (draw_engine.h), kept beside whichever scene above is set: the
  // same file as an engine sees it.
  void set_engine_scene(const EngineScene& scene);
  // Only what Method::kEngine draws: any scene above is dropped (its textures freed), so that a
  // caller drawing by the engine method alone (the bake's measuring) uploads nothing else.
  void set_engine_only(const EngineScene& scene);

  // Draws one frame (cleared first). Returns what was drawn.
  DrawStats draw(const Camera& camera, const DrawSettings& settings);
  // The frame as RGBA, rows top to bottom.
  Image read_pixels() const;
  void resize(int width, int height);  // window mode

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace qf::render
