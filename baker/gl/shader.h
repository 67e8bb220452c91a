// GLSL shader compilation for the two shader users, the GL depth-peeling sampler and the
// renderer's engine method. Needs a current context.
#pragma once

#include <GL/gl.h>

namespace qf {

// A compiled shader of `type` (GL_VERTEX_SHADER, GL_FRAGMENT_SHADER); throws std::runtime_error
// "WHAT: shader does not compile: LOG" with the driver's log.
GLuint compile_shader(GLenum type, const char* source, const char* what);

}  // namespace qf
