// GL 1.1 fixed-function drawing (see draw_gl11.h). Each Pass of blend_order.h maps to one state
// block below; state is switched only when the pass changes, because each switch costs ~5 us on
// llvmpipe (gl-notes.md 2). The framebuffer object (GL 3.0) is the only post-1.1 call: it is the
// headless render target, not part of the drawing.
#define GL_GLEXT_PROTOTYPES
#include "runtime_gl/draw_gl11.h"

#include "runtime_gl/draw_engine.h"
#include "runtime_gl/mip_chain.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace qf::render {

float normalize_threshold(const DrawSettings& s) {
  // Only where colour and coverage are plain sums: the back-face methods darken both, which a
  // division would undo.
  if (s.method != Method::kOverlap && s.method != Method::kTwoPass && s.method != Method::kBlendAll) return 0;
  return s.normalize < 0 ? (s.method == Method::kOverlap ? kDefaultNormalize : 0.0f) : s.normalize;
}

// The normalising composite (DrawSettings::normalize), and the strength the quads are drawn at
// meanwhile.
bool normalizing(const DrawSettings& s) { return normalize_threshold(s) > 0; }
constexpr float kNormalizeHeadroom = 0.5f;

namespace {

GLuint upload_texture(const Image& image, bool premultiply) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  const std::vector<Image> chain = mip_chain(image, premultiply);
  for (std::size_t l = 0; l < chain.size(); ++l)
    glTexImage2D(GL_TEXTURE_2D, static_cast<GLint>(l), GL_RGBA8, chain[l].width, chain[l].height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 chain[l].rgba.data());
  // The glTF sampler: trilinear, clamped (the atlas gutters keep tiles apart).
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

// The splat footprint: a disc in a 32x32 alpha texture, cut at alpha 0.5 by the alpha test.
GLuint disc_texture() {
  constexpr int kSide = 32;
  std::vector<std::uint8_t> a(kSide * kSide);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const float u = (x + 0.5f) / kSide * 2 - 1, v = (y + 0.5f) / kSide * 2 - 1;
      // Linear ramp across the rim so bilinear filtering puts the 0.5 crossing at radius 1.
      const float r = std::sqrt(u * u + v * v);
      a[static_cast<std::size_t>(y * kSide + x)] = static_cast<std::uint8_t>(std::clamp(0.5f + (1 - r) * kSide * 0.5f, 0.0f, 1.0f) * 255);
    }
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_ALPHA8, kSide, kSide, 0, GL_ALPHA, GL_UNSIGNED_BYTE, a.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

// Any unit vector perpendicular to n.
Vec3f perpendicular(Vec3f n) {
  const Vec3f a = std::fabs(n.x) < 0.9f ? Vec3f{1, 0, 0} : Vec3f{0, 1, 0};
  return normalized(cross(n, a));
}

float median_half_diagonal(const ImpostorScene& s) {
  std::vector<float> h;
  for (const Item& it : s.items) {
    float r2 = 0;
    for (std::uint32_t v = it.first_vertex; v < it.first_vertex + it.vertex_count; ++v) {
      const Vec3f p{s.positions[v * 3], s.positions[v * 3 + 1], s.positions[v * 3 + 2]};
      const Vec3f d = p - it.center;
      r2 = std::max(r2, dot(d, d));
    }
    h.push_back(std::sqrt(r2));
  }
  if (h.empty()) return 0;
  std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2), h.end());
  return h[h.size() / 2];
}

// One pass's state block (blend_order.h Pass): colour and depth masks, depth test, the view
// (offset for the depth-offset pass), blending, the alpha test, and the colour the texels are
// multiplied by (the premultiplied passes' strength a, on all four channels).
void set_pass_state(Pass pass, const Mat4& view, float alpha_ref, float strength) {
  const bool color = pass != Pass::kLock && pass != Pass::kDepthOffset;
  const bool depth_test = pass != Pass::kDarkenHard && pass != Pass::kDarkenSoft && pass != Pass::kAddNoDepth;
  const bool depth_write = pass == Pass::kLock || pass == Pass::kDepthOffset || pass == Pass::kOpaque;
  glColorMask(color, color, color, color);
  glDepthMask(depth_write ? GL_TRUE : GL_FALSE);
  if (depth_test) glEnable(GL_DEPTH_TEST);
  else glDisable(GL_DEPTH_TEST);
  glLoadMatrixf(view.data());
  // Blending. Premultiplied texels times (a, a, a, a): colour and coverage both scale by a.
  switch (pass) {
    case Pass::kColor:
    case Pass::kAddNoDepth: glEnable(GL_BLEND), glBlendFunc(GL_ONE, GL_ONE); break;
    case Pass::kDarkenHard: glEnable(GL_BLEND), glBlendFunc(GL_ZERO, GL_ZERO); break;
    case Pass::kDarkenSoft: glEnable(GL_BLEND), glBlendFunc(GL_ZERO, GL_ONE_MINUS_SRC_ALPHA); break;
    default: glDisable(GL_BLEND); break;
  }
  // Alpha test.
  glEnable(GL_ALPHA_TEST);
  switch (pass) {
    case Pass::kLock: glAlphaFunc(GL_GREATER, alpha_ref); break;
    case Pass::kDepthOffset:
    case Pass::kDarkenHard: glAlphaFunc(GL_GREATER, 0.0f); break;
    case Pass::kOpaque: glAlphaFunc(GL_GREATER, alpha_ref); break;
    default: glDisable(GL_ALPHA_TEST); break;
  }
  glColor4f(strength, strength, strength, strength);
}

}  // namespace

struct Renderer::Impl {
  int width = 0, height = 0;
  bool offscreen = true;
  GLuint fbo = 0, color_rb = 0, depth_rb = 0;
  // The current scene: exactly one of the three.
  const ImpostorScene* impostor = nullptr;
  const SplatScene* splats = nullptr;
  const MeshScene* mesh = nullptr;
  const PointImpostorScene* points = nullptr;
  const ClusterScene* cluster = nullptr;
  std::unique_ptr<EngineDrawer> engine;  // made on first use (compiles shaders)
  bool has_engine_scene = false;
  std::vector<GLuint> straight, premultiplied;  // per impostor texture
  GLuint disc = 0;
  std::vector<float> splat_pos, splat_nrm, splat_uv;  // 4 corners per splat
  std::vector<std::uint8_t> splat_rgba, mesh_rgba;

  void make_framebuffer() {
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &color_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, color_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb);
    glGenRenderbuffers(1, &depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("the off-screen framebuffer is incomplete");
  }
  void free_framebuffer() {
    if (!fbo) return;
    glDeleteRenderbuffers(1, &color_rb);
    glDeleteRenderbuffers(1, &depth_rb);
    glDeleteFramebuffers(1, &fbo);
    fbo = 0;
  }
  void free_textures() {
    if (!straight.empty()) glDeleteTextures(static_cast<GLsizei>(straight.size()), straight.data());
    if (!premultiplied.empty()) glDeleteTextures(static_cast<GLsizei>(premultiplied.size()), premultiplied.data());
    straight.clear();
    premultiplied.clear();
    impostor = nullptr;
    splats = nullptr;
    mesh = nullptr;
    points = nullptr;
    cluster = nullptr;
  }

  void setup_camera_and_light(const Camera& c, bool lighting) {
    glViewport(0, 0, width, height);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(c.projection().data());
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    // A headlight: directional, from the eye (set under the identity so it stays in eye space).
    const GLfloat dir[4] = {0, 0, 1, 0}, diffuse[4] = {0.7f, 0.7f, 0.7f, 1}, ambient[4] = {0.3f, 0.3f, 0.3f, 1},
                  none[4] = {0, 0, 0, 1};
    glLightfv(GL_LIGHT0, GL_POSITION, dir);
    glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
    glLightfv(GL_LIGHT0, GL_SPECULAR, none);
    glLightfv(GL_LIGHT0, GL_AMBIENT, none);
    glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
    glEnable(GL_LIGHT0);
    glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    glEnable(GL_COLOR_MATERIAL);
    if (lighting) glEnable(GL_LIGHTING);
    else glDisable(GL_LIGHTING);
    glLoadMatrixf(c.view().data());
  }

  void draw_impostor(const Camera& c, const DrawSettings& s, DrawStats& stats);
  void draw_splats();
  void draw_mesh();
  void draw_points(const Camera& c, DrawStats& stats);
  void draw_thick_lines(const Camera& c, DrawStats& stats);
  std::vector<std::uint8_t> point_rgba;
  void composite_background(Rgb8 bg);
  void normalize_and_composite(Rgb8 bg, float floor, float transparency);
};

Renderer::Renderer(int width, int height, bool offscreen) : impl_(std::make_unique<Impl>()) {
  impl_->width = width;
  impl_->height = height;
  impl_->offscreen = offscreen;
  if (offscreen) impl_->make_framebuffer();
  impl_->disc = disc_texture();
}

Renderer::~Renderer() {
  impl_->engine.reset();
  impl_->free_textures();
  glDeleteTextures(1, &impl_->disc);
  impl_->free_framebuffer();
}

void Renderer::resize(int width, int height) {
  impl_->width = width;
  impl_->height = height;
  if (impl_->offscreen) {
    impl_->free_framebuffer();
    impl_->make_framebuffer();
  }
}

void Renderer::set_scene(const ImpostorScene& scene) {
  impl_->free_textures();
  impl_->impostor = &scene;
  for (const Image& t : scene.textures) {
    impl_->straight.push_back(upload_texture(t, false));
    impl_->premultiplied.push_back(upload_texture(t, true));
  }
}

void Renderer::set_scene(const SplatScene& scene) {
  impl_->free_textures();
  impl_->splats = &scene;
  Impl& m = *impl_;
  const std::size_t n = scene.positions.size();
  m.splat_pos.resize(n * 12);
  m.splat_nrm.resize(n * 12);
  m.splat_uv.resize(n * 8);
  m.splat_rgba.resize(n * 16);
  const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3f nrm = scene.normals[i], u = perpendicular(nrm), v = cross(nrm, u);
    const float r = scene.radii[i];
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec3f p = scene.positions[i] + u * (su[k] * r) + v * (sv[k] * r);
      for (int a = 0; a < 3; ++a) {
        m.splat_pos[(i * 4 + k) * 3 + static_cast<std::size_t>(a)] = p[a];
        m.splat_nrm[(i * 4 + k) * 3 + static_cast<std::size_t>(a)] = nrm[a];
      }
      m.splat_uv[(i * 4 + k) * 2] = su[k] * 0.5f + 0.5f;
      m.splat_uv[(i * 4 + k) * 2 + 1] = sv[k] * 0.5f + 0.5f;
      const Rgb8 col = scene.colors[i];
      const std::uint8_t rgba[4] = {col.r, col.g, col.b, 255};
      std::copy(rgba, rgba + 4, &m.splat_rgba[(i * 4 + k) * 4]);
    }
  }
}

void Renderer::set_scene(const MeshScene& scene) {
  impl_->free_textures();
  impl_->mesh = &scene;
  std::vector<std::uint8_t>& rgba = impl_->mesh_rgba;
  rgba.assign(scene.colors.size() * 4, 255);
  for (std::size_t i = 0; i < scene.colors.size(); ++i) {
    rgba[i * 4] = scene.colors[i].r;
    rgba[i * 4 + 1] = scene.colors[i].g;
    rgba[i * 4 + 2] = scene.colors[i].b;
  }
}

void Renderer::set_scene(const PointImpostorScene& scene, const MeshScene* mesh) {
  if (mesh) set_scene(*mesh);  // the mesh's colours, for the fade
  else impl_->free_textures();
  impl_->points = &scene;
  impl_->point_rgba.assign(scene.colors.size() * 4, 255);
  for (std::size_t i = 0; i < scene.colors.size(); ++i) {
    impl_->point_rgba[i * 4] = scene.colors[i].r;
    impl_->point_rgba[i * 4 + 1] = scene.colors[i].g;
    impl_->point_rgba[i * 4 + 2] = scene.colors[i].b;
  }
}

void Renderer::set_scene(const ClusterScene& scene) {
  set_scene(scene.mesh);
  impl_->cluster = &scene;
}

void Renderer::set_engine_scene(const EngineScene& scene) {
  if (!impl_->engine) impl_->engine = std::make_unique<EngineDrawer>();
  impl_->engine->set_scene(scene);
  impl_->has_engine_scene = true;
}

void Renderer::set_engine_only(const EngineScene& scene) {
  impl_->free_textures();
  set_engine_scene(scene);
}

void Renderer::Impl::draw_thick_lines(const Camera& c, DrawStats& stats) {
  const ClusterScene& sc = *cluster;
  const double z0 = c.focal_pixels();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  for (std::size_t e = 0; e < sc.thickness.size(); ++e) {
    const Vec3f a = sc.line_positions[2 * e], b = sc.line_positions[2 * e + 1];
    const double r = length((a + b) * 0.5f - c.eye) / z0;  // R: model size of a pixel there
    const float line_width = static_cast<float>(std::clamp(sc.thickness[e] / r, 1.0, 64.0));
    // Perpendicular to the line, in the plane of the line and the eye, towards the eye.
    const Vec3f n = normalized(cross(cross(a - c.eye, b - c.eye), b - a));
    glLineWidth(line_width);
    glBegin(GL_LINES);
    glNormal3f(n.x, n.y, n.z);
    for (int k = 0; k < 2; ++k) {
      const Rgb8 col = sc.line_colors[2 * e + static_cast<std::size_t>(k)];
      glColor3ub(col.r, col.g, col.b);
      const Vec3f p = k ? b : a;
      glVertex3f(p.x, p.y, p.z);
    }
    glEnd();
    ++stats.other_draws;
  }
  glLineWidth(1);
  if (!sc.points.empty()) {
    glDisable(GL_LIGHTING);
    glPointSize(1);
    glBegin(GL_POINTS);
    for (std::size_t i = 0; i < sc.points.size(); ++i) {
      glColor3ub(sc.point_colors[i].r, sc.point_colors[i].g, sc.point_colors[i].b);
      glVertex3f(sc.points[i].x, sc.points[i].y, sc.points[i].z);
    }
    glEnd();
  }
}

// The first N = N0 (s Z0 / d)^2 of the randomly ordered points, as smooth 2.5-pixel points: each
// then stands for about one pixel of surface (paper 5), and discs of 2.5 pixels leave
// exp(-pi 2.5^2 / 4) = 0.7% of it uncovered (2 pixels: 4%, visible specks). d is the distance to the bounding box's
// centre. Nearer than s Z0 all N0 are drawn, fading over the mesh (when there is one) down to
// 0.7 s Z0, where the mesh alone remains.
void Renderer::Impl::draw_points(const Camera& c, DrawStats& stats) {
  const PointImpostorScene& p = *points;
  const float d = length(c.eye - p.bounds.center());
  const double z0 = c.focal_pixels();
  const double d_switch = p.pixel * z0;
  float weight = 1;
  if (mesh) weight = static_cast<float>(std::clamp((d - 0.7 * d_switch) / (0.3 * d_switch), 0.0, 1.0));
  stats.points_weight = weight;
  if (weight < 1) draw_mesh();
  if (weight <= 0) return;
  const std::size_t n = points_to_draw(p.positions.size(), p.pixel, d, z0);
  stats.points = n;
  const auto alpha = static_cast<std::uint8_t>(std::lround(weight * 255));
  for (std::size_t i = 0; i < n; ++i) point_rgba[i * 4 + 3] = alpha;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_POINT_SMOOTH);
  glPointSize(2.5f);
  glEnable(GL_BLEND);  // smooth points are antialiased through their coverage alpha
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, p.positions.data());
  glNormalPointer(GL_FLOAT, 0, p.normals.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, point_rgba.data());
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisable(GL_BLEND);
  glDisable(GL_POINT_SMOOTH);
  ++stats.other_draws;
}

// Oriented, depth-tested splats, as QSplat draws them: opaque discs cut by the alpha test.
void Renderer::Impl::draw_splats() {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, disc);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glEnable(GL_ALPHA_TEST);
  glAlphaFunc(GL_GREATER, 0.5f);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, splat_pos.data());
  glNormalPointer(GL_FLOAT, 0, splat_nrm.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, splat_rgba.data());
  glTexCoordPointer(2, GL_FLOAT, 0, splat_uv.data());
  glDrawArrays(GL_QUADS, 0, static_cast<GLsizei>(splat_pos.size() / 3));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_FALSE);
}

// Triangles with smooth vertex normals and colours, lit on both sides (open meshes, soups).
void Renderer::Impl::draw_mesh() {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, mesh->positions.data());
  glNormalPointer(GL_FLOAT, 0, mesh->normals.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, mesh_rgba.data());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh->indices.size()), GL_UNSIGNED_INT, mesh->indices.data());
  glDisableClientState(GL_COLOR_ARRAY);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_FALSE);
}

void Renderer::Impl::draw_impostor(const Camera& c, const DrawSettings& s, DrawStats& stats) {
  const ImpostorScene& sc = *impostor;
  // Normalising: everything drawn at half strength, so sums of the basis up to 2 fit the 8-bit
  // framebuffer (the composite divides it out); the lock's test scales with it.
  const float headroom = normalizing(s) ? kNormalizeHeadroom : 1.0f;
  const float alpha_ref = (s.alpha_ref >= 0 ? s.alpha_ref : sc.alpha_ref) * headroom;
  const std::vector<DrawOp> ops = plan_draws(s.method, sc, c.eye);
  const float a = normalizing(s) ? headroom : std::clamp(s.transparency, 0.0f, 1.0f);
  const float offset = s.depth_offset > 0 ? s.depth_offset : 0.5f * median_half_diagonal(sc);
  Mat4 view_offset = c.view();
  view_offset[14] -= offset;  // eye-space translation along -z: further from the eye

  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, sc.positions.data());
  glNormalPointer(GL_FLOAT, 0, sc.normals.data());
  glTexCoordPointer(2, GL_FLOAT, 0, sc.uvs.data());
  // Quads seen from behind (double-sided levels) are lit with the flipped normal.
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, sc.double_sided ? GL_TRUE : GL_FALSE);
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glDepthFunc(GL_LESS);

  int bound_pass = -1;
  GLuint bound_texture = 0;
  for (const DrawOp& op : ops) {
    const bool premult = op.pass != Pass::kOpaque;
    if (static_cast<int>(op.pass) != bound_pass) {
      ++stats.state_changes;
      bound_pass = static_cast<int>(op.pass);
      set_pass_state(op.pass, op.pass == Pass::kDepthOffset ? view_offset : c.view(), alpha_ref, premult ? a : 1.0f);
    }
    const Item& it = sc.items[op.item];
    const GLuint tex = (premult ? premultiplied : straight)[it.texture];
    if (tex != bound_texture) glBindTexture(GL_TEXTURE_2D, tex), bound_texture = tex;
    glDrawArrays(GL_TRIANGLES, static_cast<GLint>(it.first_vertex), static_cast<GLsizei>(it.vertex_count));
    if (op.pass == Pass::kColor || op.pass == Pass::kAddNoDepth || op.pass == Pass::kOpaque) ++stats.color_draws;
    else if (op.pass == Pass::kLock) ++stats.lock_draws;
    else ++stats.other_draws;
  }
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_FALSE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
}

// Additive methods draw onto transparent black, accumulating coverage in alpha; the background
// then fills what is left: C = C_object + (1 - coverage) * background. So the result is right over
// any background colour, not only black.
void Renderer::Impl::composite_background(Rgb8 bg) {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_ALPHA_TEST);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glColor4ub(bg.r, bg.g, bg.b, 255);
  glBegin(GL_QUADS);
  glVertex2f(-1, -1);
  glVertex2f(1, -1);
  glVertex2f(1, 1);
  glVertex2f(-1, 1);
  glEnd();
  glDisable(GL_BLEND);
}

// The normalising composite (DrawSettings::normalize), on the CPU: read back the accumulated
// premultiplied colour C and coverage A (both drawn at `kNormalizeHeadroom` strength), so the sum of
// the basis is c = A / headroom, the mean colour C / A; write mean * k + (1 - k) * background with
// k = min(1, c / t) * transparency.
void Renderer::Impl::normalize_and_composite(Rgb8 bg, float floor, float transparency) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  // Everything but the colour depends on the 8-bit coverage alone: one table of 256 entries.
  const std::uint8_t b[3] = {bg.r, bg.g, bg.b};
  float scale[256], base[256][3];
  for (int a = 0; a < 256; ++a) {
    const float coverage = a / 255.0f, sum = coverage / kNormalizeHeadroom;
    const float k = std::min(1.0f, sum / floor) * transparency;
    scale[a] = coverage > 0 ? k / coverage : 0.0f;
    for (int ch = 0; ch < 3; ++ch) base[a][ch] = (1 - k) * b[ch] + 0.5f;  // + 0.5: round below
  }
  for (std::size_t i = 0; i < px.size(); i += 4) {
    const std::uint8_t a = px[i + 3];
    for (std::size_t ch = 0; ch < 3; ++ch)
      px[i + ch] = static_cast<std::uint8_t>(std::min(255.0f, px[i + ch] * scale[a] + base[a][ch]));
    px[i + 3] = 255;
  }
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_ALPHA_TEST);
  glDisable(GL_BLEND);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DITHER);  // the window's visual may dither written pixels; the FBO does not
  glRasterPos2f(-1, -1);
  glDrawPixels(width, height, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  glEnable(GL_DITHER);
}

DrawStats Renderer::draw(const Camera& camera, const DrawSettings& s) {
  Impl& m = *impl_;
  if (m.offscreen) glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
  const bool engine = s.method == Method::kEngine;
  if (engine && !m.has_engine_scene) throw std::logic_error("Renderer::draw: the engine method needs set_engine_scene");
  const bool additive = !engine && m.impostor && is_additive(s.method);
  const float inv = 1.0f / 255;
  if (additive) glClearColor(0, 0, 0, 0);
  else glClearColor(s.background.r * inv, s.background.g * inv, s.background.b * inv, engine && s.coverage_alpha ? 0 : 1);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_ALPHA_TEST);
  m.setup_camera_and_light(camera, s.lighting);
  DrawStats stats;
  if (engine) stats.color_draws = m.engine->draw(camera, s.lights, s.alpha_mode, s.alpha_cutoff, s.mipmaps);
  else if (m.impostor) m.draw_impostor(camera, s, stats);
  else if (m.points) m.draw_points(camera, stats);
  else if (m.splats) m.draw_splats();
  else if (m.mesh) {
    m.draw_mesh();
    if (m.cluster) m.draw_thick_lines(camera, stats);
  }
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_ALPHA_TEST);
  if (additive && normalizing(s)) m.normalize_and_composite(s.background, normalize_threshold(s), std::clamp(s.transparency, 0.0f, 1.0f));
  else if (additive) m.composite_background(s.background);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  return stats;
}

Image Renderer::read_pixels() const {
  const Impl& m = *impl_;
  Image img;
  img.width = m.width;
  img.height = m.height;
  img.rgba.resize(static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height) * 4);
  std::vector<std::uint8_t> raw(img.rgba.size());
  glFinish();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, m.width, m.height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  // GL rows are bottom-up.
  const std::size_t row = static_cast<std::size_t>(m.width) * 4;
  for (int y = 0; y < m.height; ++y)
    std::copy_n(&raw[static_cast<std::size_t>(m.height - 1 - y) * row], row, &img.rgba[static_cast<std::size_t>(y) * row]);
  return img;
}

}  // namespace qf::render
