// EGL contexts, headless and windowed (see egl_context.h).
#include "runtime_gl/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <X11/Xlib.h>

#include <stdexcept>

namespace qf::render {
namespace {

std::string egl_error(const char* what) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04x", eglGetError());
  return std::string("EGL: ") + what + " failed (error " + hex + ")";
}

// A compatibility-profile context (fixed function) on `display`, for surfaces of `surface_bit`.
EGLContext make_context(EGLDisplay display, EGLint surface_bit, EGLConfig* config_out) {
  if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(egl_error("eglBindAPI(OpenGL)"));
  const EGLint attribs[] = {EGL_SURFACE_TYPE, surface_bit, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                            EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLint count = 0;
  if (!eglChooseConfig(display, attribs, config_out, 1, &count) || count < 1) throw std::runtime_error(egl_error("eglChooseConfig"));
  const EGLint ctx_attribs[] = {EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(display, *config_out, EGL_NO_CONTEXT, ctx_attribs);
  if (ctx == EGL_NO_CONTEXT) throw std::runtime_error(egl_error("eglCreateContext"));
  return ctx;
}

EGLDisplay platform_display(EGLenum platform, void* native) {
  auto get = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get) throw std::runtime_error("EGL: eglGetPlatformDisplayEXT is not available");
  EGLDisplay d = get(platform, native, nullptr);
  if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr)) throw std::runtime_error(egl_error("eglInitialize"));
  return d;
}

}  // namespace

struct HeadlessContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

HeadlessContext::HeadlessContext() : impl_(std::make_unique<Impl>()) {
  // Surfaceless Mesa: no X, no Wayland, no environment variables (gl-notes.md 1).
  impl_->display = platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY);
  EGLConfig config;
  impl_->context = make_context(impl_->display, EGL_PBUFFER_BIT, &config);
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context))
    throw std::runtime_error(egl_error("eglMakeCurrent"));
}

HeadlessContext::~HeadlessContext() {
  eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(impl_->display, impl_->context);
  eglTerminate(impl_->display);
  eglReleaseThread();  // lets llvmpipe's rasterizer threads go
}

std::string HeadlessContext::renderer() const { return reinterpret_cast<const char*>(glGetString(GL_RENDERER)); }

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
  m.display = platform_display(EGL_PLATFORM_X11_KHR, m.x);
  EGLConfig config;
  m.context = make_context(m.display, EGL_WINDOW_BIT, &config);
  m.surface = eglCreateWindowSurface(m.display, config, static_cast<EGLNativeWindowType>(m.window), nullptr);
  if (m.surface == EGL_NO_SURFACE) throw std::runtime_error(egl_error("eglCreateWindowSurface"));
  if (!eglMakeCurrent(m.display, m.surface, m.surface, m.context)) throw std::runtime_error(egl_error("eglMakeCurrent"));
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
