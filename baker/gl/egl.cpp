// Headless EGL context and helpers (see egl.h).
#include "gl/egl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>

#include <cstdio>
#include <stdexcept>

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#include <link.h>

#include <cstring>
#include <vector>
#endif

namespace qf {
namespace egl {

std::string error(const char* what) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04x", eglGetError());
  return std::string("EGL: ") + what + " failed (error " + hex + ")";
}

// A compatibility-profile context (fixed function) on `display`, for surfaces of `surface_bit`.
void* make_context(void* display, int surface_bit, void** config_out) {
  if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(error("eglBindAPI(OpenGL)"));
  const EGLint attribs[] = {EGL_SURFACE_TYPE, surface_bit, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                            EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLint count = 0;
  if (!eglChooseConfig(display, attribs, config_out, 1, &count) || count < 1) throw std::runtime_error(error("eglChooseConfig"));
  const EGLint ctx_attribs[] = {EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(display, *config_out, EGL_NO_CONTEXT, ctx_attribs);
  if (ctx == EGL_NO_CONTEXT) throw std::runtime_error(error("eglCreateContext"));
  return ctx;
}

#if defined(__SANITIZE_ADDRESS__)
// AddressSanitizer builds only (QF_SANITIZE): the Mesa driver eglInitialize loaded (a path under
// .../dri/, e.g. swrast_dri.so for llvmpipe) stays mapped after eglTerminate (RTLD_NODELETE).
// LeakSanitizer looks for pointers in the globals of the modules still mapped at exit: once the
// driver is unmapped, the blocks its globals hold (a realloc'ed 128 bytes, two 56-byte callocs)
// read as leaks from an unknown module, which no suppression can name (tests/lsan.supp).
void pin_gl_drivers() {
  std::vector<std::string> drivers;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* out) {
        if (info->dlpi_name && std::strstr(info->dlpi_name, "/dri/"))
          static_cast<std::vector<std::string>*>(out)->push_back(info->dlpi_name);
        return 0;
      },
      &drivers);
  for (const std::string& d : drivers) dlopen(d.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}
#endif

void* platform_display(unsigned platform, void* native) {
  auto get = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get) throw std::runtime_error("EGL: eglGetPlatformDisplayEXT is not available");
  EGLDisplay d = get(platform, native, nullptr);
  if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr)) throw std::runtime_error(error("eglInitialize"));
#if defined(__SANITIZE_ADDRESS__)
  pin_gl_drivers();
#endif
  return d;
}

}  // namespace egl

struct HeadlessContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

HeadlessContext::HeadlessContext() : impl_(std::make_unique<Impl>()) {
  // Surfaceless Mesa: no X, no Wayland, no environment variables (gl-notes.md 1).
  impl_->display = egl::platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY);
  void* config = nullptr;
  impl_->context = egl::make_context(impl_->display, EGL_PBUFFER_BIT, &config);
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context))
    throw std::runtime_error(egl::error("eglMakeCurrent"));
}

HeadlessContext::~HeadlessContext() {
  eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(impl_->display, impl_->context);
  eglTerminate(impl_->display);
  eglReleaseThread();  // lets llvmpipe's rasterizer threads go
}

std::string HeadlessContext::renderer() const { return reinterpret_cast<const char*>(glGetString(GL_RENDERER)); }
std::string HeadlessContext::version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }

}  // namespace qf
