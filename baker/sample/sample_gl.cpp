// Depth peeling with OpenGL through EGL (sample.h; gl-notes.md 3): per axis an orthographic view
// of the mesh, every layer drawn into an FBO whose colour is the triangle id and whose depth is a
// 32-bit float texture; a GLSL test discards what is not strictly behind the previous layer
// (exact with D32F: no epsilon, no re-peeling). An occlusion query stops the peeling when a layer
// is empty. The only file of the sampler with GL calls.
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <stdexcept>
#include <string>

#include "gl/shader.h"
#include "gl/egl.h"
#include "sample/sample.h"

namespace qf {
namespace {

// Triangle id + 1 in RGBA8 (0 = no fragment); flat, so the bytes pass through exactly.
const char* kVertexShader = R"(#version 130
in vec3 position;
in vec4 id;
uniform mat4 mvp;
flat out vec4 v_id;
void main() { gl_Position = mvp * vec4(position, 1.0); v_id = id; })";

const char* kFragmentShader = R"(#version 130
flat in vec4 v_id;
uniform sampler2D previous;
uniform int first;
out vec4 color;
void main() {
  if (first == 0 && gl_FragCoord.z <= texelFetch(previous, ivec2(gl_FragCoord.xy), 0).r) discard;
  color = v_id;
})";

// GL objects of one peeling run, released on every exit path.
struct PeelTarget {
  GLuint program = 0, fbo = 0, color = 0, depth[2] = {0, 0}, vbo[2] = {0, 0}, query = 0;
  ~PeelTarget() {
    glDeleteQueries(1, &query);
    glDeleteBuffers(2, vbo);
    glDeleteTextures(2, depth);
    glDeleteTextures(1, &color);
    glDeleteFramebuffers(1, &fbo);
    glDeleteProgram(program);
  }
};

void make_program(PeelTarget& t) {
  t.program = glCreateProgram();
  const GLuint vs = compile_shader(GL_VERTEX_SHADER, kVertexShader, "depth peeling"), fs = compile_shader(GL_FRAGMENT_SHADER, kFragmentShader, "depth peeling");
  glAttachShader(t.program, vs);
  glAttachShader(t.program, fs);
  glBindAttribLocation(t.program, 0, "position");
  glBindAttribLocation(t.program, 1, "id");
  glBindFragDataLocation(t.program, 0, "color");
  glLinkProgram(t.program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(t.program, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("depth peeling shader did not link");
}

GLuint make_texture(GLenum internal, GLenum format, GLenum type, int w, int h) {
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  // In a compatibility context DEPTH_TEXTURE_MODE also applies to GLSL: keep depth in .r.
  if (format == GL_DEPTH_COMPONENT) glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_TEXTURE_MODE, GL_LUMINANCE);
  glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal), w, h, 0, format, type, nullptr);
  return tex;
}

// 1. The triangles of this axis as a vertex array, relative to the grid corner (float precision
//    where it matters), ids as RGBA bytes, bound to attributes 0 and 1. Returns the vertex count.
GLsizei upload_triangles(const TriangleMesh& mesh, const SampleGrid& grid, const SampleOptions& options, int axis, PeelTarget& t) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  std::vector<float> pos;
  std::vector<unsigned char> ids;
  for (std::size_t tri = 0; tri < mesh.triangles.size(); ++tri) {
    if (options.per_axis_triangles && sampling_axis(mesh, tri) != axis) continue;
    const std::uint32_t id = static_cast<std::uint32_t>(tri) + 1;
    for (std::uint32_t k : mesh.triangles[tri]) {
      const Vec3f p = mesh.positions[k] - grid.origin;
      pos.insert(pos.end(), {p[u], p[v], p[axis]});
      ids.insert(ids.end(), {static_cast<unsigned char>(id), static_cast<unsigned char>(id >> 8),
                             static_cast<unsigned char>(id >> 16), static_cast<unsigned char>(id >> 24)});
    }
  }
  glBindBuffer(GL_ARRAY_BUFFER, t.vbo[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(pos.size() * sizeof(float)), pos.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, t.vbo[1]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(ids.size()), ids.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, 0, nullptr);
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  return static_cast<GLsizei>(pos.size() / 3);
}

// 2. Orthographic: image u, v over the grid, depth over the grid's extent along the axis; the
//    colour and both depth textures sized to the image, the colour attached to the FBO.
void set_view(const SampleGrid& grid, int axis, const AxisLayers& L, PeelTarget& t) {
  const float W = static_cast<float>(L.width) * grid.pixel, H = static_cast<float>(L.height) * grid.pixel;
  const float D = static_cast<float>(grid.cells[static_cast<std::size_t>(axis)]) * grid.pixel;
  const float mvp[16] = {2 / W, 0, 0, 0, 0, 2 / H, 0, 0, 0, 0, 2 / D, 0, -1, -1, -1, 1};  // column-major
  glUniformMatrix4fv(glGetUniformLocation(t.program, "mvp"), 1, GL_FALSE, mvp);
  glViewport(0, 0, L.width, L.height);
  glBindTexture(GL_TEXTURE_2D, t.color);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, L.width, L.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  for (GLuint d : t.depth) {
    glBindTexture(GL_TEXTURE_2D, d);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, L.width, L.height, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.color, 0);
}

// 3. Peel: layer k writes depth[k % 2] and tests against depth[(k + 1) % 2]. Per layer, each
//    pixel's triangle id + 1 (0: none), until a layer is empty or max_layers are drawn.
std::vector<std::vector<std::uint32_t>> peel(const AxisLayers& L, int max_layers, GLsizei vertices, PeelTarget& t) {
  const std::size_t pixels = static_cast<std::size_t>(L.width) * static_cast<std::size_t>(L.height);
  std::vector<std::vector<std::uint32_t>> layer_ids;
  std::vector<unsigned char> rgba(pixels * 4);
  for (int k = 0; k < max_layers; ++k) {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t.depth[k % 2], 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("depth peeling framebuffer incomplete");
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, t.depth[(k + 1) % 2]);
    glUniform1i(glGetUniformLocation(t.program, "first"), k == 0);
    glBeginQuery(GL_SAMPLES_PASSED, t.query);
    glDrawArrays(GL_TRIANGLES, 0, vertices);
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint passed = 0;
    glGetQueryObjectuiv(t.query, GL_QUERY_RESULT, &passed);
    if (passed == 0) break;
    glReadPixels(0, 0, L.width, L.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    std::vector<std::uint32_t> id(pixels);
    for (std::size_t p = 0; p < pixels; ++p)
      id[p] = rgba[4 * p] | rgba[4 * p + 1] << 8 | rgba[4 * p + 2] << 16 | static_cast<std::uint32_t>(rgba[4 * p + 3]) << 24;
    layer_ids.push_back(std::move(id));
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  return layer_ids;
}

// 4. Per pixel, its layers front to back (a pixel's layers are contiguous from the first).
void gather_layers(const std::vector<std::vector<std::uint32_t>>& layer_ids, AxisLayers& L) {
  const std::size_t pixels = static_cast<std::size_t>(L.width) * static_cast<std::size_t>(L.height);
  L.layers = static_cast<int>(layer_ids.size());
  L.offsets.assign(pixels + 1, 0);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (const auto& layer : layer_ids) {
      if (layer[p] == 0) break;
      L.triangles.push_back(layer[p] - 1);
    }
    L.offsets[p + 1] = static_cast<std::uint32_t>(L.triangles.size());
  }
}

// One axis's layered depth image: every layer of the mesh's triangles seen along `axis` (only those
// sampled on it with per_axis_triangles), over the grid, in the GL objects of `t`.
AxisLayers peel_axis(const TriangleMesh& mesh, const SampleGrid& grid, const SampleOptions& options, int axis, PeelTarget& t) {
  AxisLayers L = empty_layers(grid, axis);
  const GLsizei vertices = upload_triangles(mesh, grid, options, axis, t);
  set_view(grid, axis, L, t);
  gather_layers(peel(L, options.max_layers, vertices, t), L);
  return L;
}

}  // namespace

std::array<AxisLayers, 3> peel_layers_gl(const TriangleMesh& mesh, const SampleGrid& grid, const SampleOptions& options) {
  HeadlessContext context;
  PeelTarget t;
  make_program(t);
  glUseProgram(t.program);
  glUniform1i(glGetUniformLocation(t.program, "previous"), 0);
  glGenFramebuffers(1, &t.fbo);
  glGenBuffers(2, t.vbo);
  glGenQueries(1, &t.query);
  t.color = make_texture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 1, 1);
  for (GLuint& d : t.depth) d = make_texture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, 1, 1);
  glDisable(GL_CULL_FACE);  // every layer, front- and back-facing
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::array<AxisLayers, 3> out;
  for (int axis = 0; axis < 3; ++axis) out[static_cast<std::size_t>(axis)] = peel_axis(mesh, grid, options, axis, t);
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("depth peeling: a GL call failed");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return out;
}

}  // namespace qf
