// The window of `qf-render view`: an X11 window with an EGL window surface, the runtime's only
// X11 calls. Headless rendering uses qf::HeadlessContext (baker/gl/egl.h).
#pragma once

#include <memory>
#include <string>

#include "gl/egl.h"

namespace qf::render {

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
