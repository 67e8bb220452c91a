// OpenGL contexts through EGL: the only runtime file with EGL (and X11) calls. Headless:
// surfaceless Mesa display + compatibility context, drawing into a framebuffer object
// (gl-notes.md 1). Window: an X11 window with an EGL window surface, for `qf-render view`.
#pragma once

#include <memory>
#include <string>

namespace qf::render {

// A current GL compatibility context with no surface. Throws std::runtime_error with EGL's reason
// when no context can be made.
class HeadlessContext {
 public:
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Mouse and keyboard since the last poll, in window pixels.
struct WindowEvents {
  bool close = false;
  int drag_dx = 0, drag_dy = 0;  // left button held
  int wheel = 0;                 // +1 per notch towards the user (zoom in)
  int width = 0, height = 0;     // current size
};

// A window on the X display named by DISPLAY, with a current GL context. Throws
// std::runtime_error when there is no display.
class WindowContext {
 public:
  WindowContext(int width, int height, const std::string& title);
  ~WindowContext();
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;
  WindowEvents poll();
  void swap();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace qf::render
