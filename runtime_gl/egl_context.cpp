// The X11 + EGL window of `qf-render view` (see egl_context.h).
#include "runtime_gl/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <X11/Xlib.h>

#include <stdexcept>

#include "gl/egl.h"

namespace qf::render {

struct WindowContext::Impl {
  Display* x = nullptr;
  Window window = 0;
  Atom wm_delete = 0;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
  int width = 0, height = 0, last_x = 0, last_y = 0;
  bool dragging = false;
};

WindowContext::WindowContext(int width, int height, const std::string& title) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.x = XOpenDisplay(nullptr);
  if (!m.x) throw std::runtime_error("cannot open the X display (is DISPLAY set?)");
  m.width = width;
  m.height = height;
  m.window = XCreateSimpleWindow(m.x, DefaultRootWindow(m.x), 0, 0, static_cast<unsigned>(width), static_cast<unsigned>(height), 0, 0, 0);
  XSelectInput(m.x, m.window, ButtonPressMask | ButtonReleaseMask | PointerMotionMask | KeyPressMask | StructureNotifyMask);
  XStoreName(m.x, m.window, title.c_str());
  m.wm_delete = XInternAtom(m.x, "WM_DELETE_WINDOW", False);
  XSetWMProtocols(m.x, m.window, &m.wm_delete, 1);
  XMapWindow(m.x, m.window);
  m.display = egl::platform_display(EGL_PLATFORM_X11_KHR, m.x);
  void* config = nullptr;
  m.context = egl::make_context(m.display, EGL_WINDOW_BIT, &config);
  m.surface = eglCreateWindowSurface(m.display, config, static_cast<EGLNativeWindowType>(m.window), nullptr);
  if (m.surface == EGL_NO_SURFACE) throw std::runtime_error(egl::error("eglCreateWindowSurface"));
  if (!eglMakeCurrent(m.display, m.surface, m.surface, m.context)) throw std::runtime_error(egl::error("eglMakeCurrent"));
}

WindowContext::~WindowContext() {
  Impl& m = *impl_;
  eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (m.surface != EGL_NO_SURFACE) eglDestroySurface(m.display, m.surface);
  if (m.context != EGL_NO_CONTEXT) eglDestroyContext(m.display, m.context);
  if (m.display != EGL_NO_DISPLAY) eglTerminate(m.display);
  eglReleaseThread();
  if (m.window) XDestroyWindow(m.x, m.window);
  XCloseDisplay(m.x);
}

WindowEvents WindowContext::poll() {
  Impl& m = *impl_;
  WindowEvents e;
  while (XPending(m.x)) {
    XEvent ev;
    XNextEvent(m.x, &ev);
    switch (ev.type) {
      case ButtonPress:
        if (ev.xbutton.button == Button1) m.dragging = true, m.last_x = ev.xbutton.x, m.last_y = ev.xbutton.y;
        if (ev.xbutton.button == Button4) ++e.wheel;
        if (ev.xbutton.button == Button5) --e.wheel;
        break;
      case ButtonRelease:
        if (ev.xbutton.button == Button1) m.dragging = false;
        break;
      case MotionNotify:
        if (m.dragging) {
          e.drag_dx += ev.xmotion.x - m.last_x;
          e.drag_dy += ev.xmotion.y - m.last_y;
          m.last_x = ev.xmotion.x;
          m.last_y = ev.xmotion.y;
        }
        break;
      case KeyPress:
        if (XLookupKeysym(&ev.xkey, 0) == 'q' || XLookupKeysym(&ev.xkey, 0) == 0xff1b /* Escape */) e.close = true;
        break;
      case ConfigureNotify:
        m.width = ev.xconfigure.width;
        m.height = ev.xconfigure.height;
        break;
      case ClientMessage:
        if (static_cast<Atom>(ev.xclient.data.l[0]) == m.wm_delete) e.close = true;
        break;
      default: break;
    }
  }
  e.width = m.width;
  e.height = m.height;
  return e;
}

void WindowContext::swap() { eglSwapBuffers(impl_->display, impl_->surface); }

}  // namespace qf::render
