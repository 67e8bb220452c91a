// GLSL shader compilation (see shader.h).
#define GL_GLEXT_PROTOTYPES
#include "gl/shader.h"

#include <GL/glext.h>

#include <stdexcept>
#include <string>

namespace qf {

GLuint compile_shader(GLenum type, const char* source, const char* what) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    glDeleteShader(s);
    throw std::runtime_error(std::string(what) + ": shader does not compile: " + log);
  }
  return s;
}

}  // namespace qf
