// OpenGL contexts through EGL: the project's only EGL calls besides the runtime's X11 window
// (runtime_gl/egl_context). Headless: the surfaceless Mesa display and a compatibility-profile
// context, drawing into framebuffer objects (gl-notes.md 1). The mesh sampler and the renderer
// both use it.
#pragma once

#include <memory>
#include <string>

namespace qf {

// A current GL compatibility context with no surface. Throws std::runtime_error with EGL's reason
// when no context can be made.
class HeadlessContext {
 public:
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION, e.g. "4.5 (Compatibility Profile) Mesa 22.3.6"

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

namespace egl {
// Helpers for other EGL contexts (the runtime's window). Types are EGL's, passed as void* so that
// this header does not pull in <EGL/egl.h>.
std::string error(const char* what);                                       // "EGL: what failed (error 0x....)"
void* platform_display(unsigned platform, void* native);                   // initialised EGLDisplay
void* make_context(void* display, int surface_bit, void** config_out);     // compatibility-profile EGLContext
}  // namespace egl

}  // namespace qf
