// The engine method's shaders and draw loop (see draw_engine.h).
#define GL_GLEXT_PROTOTYPES
#include "runtime_gl/draw_engine.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "gl/shader.h"

namespace qf::render {
namespace {

constexpr int kDfgSide = 16;

const char* kVertexShader = R"(#version 130
uniform mat4 u_view, u_proj;
in vec3 a_pos;
in vec3 a_nrm;
in vec4 a_tan;
in vec2 a_uv;
in vec4 a_col;
out vec3 v_view_pos;  // minus the eye-space position, as three.js's vViewPosition
out vec3 v_nrm, v_tan, v_bit;
out vec2 v_uv;
out vec4 v_col;
void main() {
  vec4 mv = u_view * vec4(a_pos, 1.0);
  v_view_pos = -mv.xyz;
  mat3 n = mat3(u_view);  // the view is a rotation + translation: its own normal matrix
  v_nrm = normalize(n * a_nrm);
  v_tan = normalize(n * a_tan.xyz);
  v_bit = normalize(cross(v_nrm, v_tan) * a_tan.w);
  v_uv = a_uv;
  v_col = a_col;
  gl_Position = u_proj * mv;
}
)";

const char* kFragmentShader = R"(#version 130
const float PI = 3.141592653589793;
uniform sampler2D u_base_map, u_normal_map, u_dfg, u_mr_map, u_ao_map, u_emissive_map;
uniform vec4 u_base_color;
uniform vec3 u_emissive;
uniform float u_metallic, u_roughness, u_normal_scale, u_cutoff, u_dir_irradiance, u_ambient_irradiance, u_ao_strength;
uniform bool u_lit, u_has_base_map, u_has_normal_map, u_has_normals, u_has_tangents, u_double_sided, u_mask, u_blend;
uniform bool u_has_mr_map, u_has_ao_map, u_has_emissive_map;
in vec3 v_view_pos;
in vec3 v_nrm, v_tan, v_bit;
in vec2 v_uv;
in vec4 v_col;

float sq(float x) { return x * x; }
vec3 fresnel(vec3 f0, float f90, float vh) {  // Schlick, with Epic's exp2 fit of (1 - vh)^5
  float f = exp2((-5.55473 * vh - 6.98316) * vh);
  return f0 * (1.0 - f) + f90 * f;
}
float smith_visibility(float a, float nl, float nv) {  // height-correlated, includes 1 / (4 nl nv)
  float a2 = a * a;
  float gv = nl * sqrt(a2 + (1.0 - a2) * nv * nv);
  float gl = nv * sqrt(a2 + (1.0 - a2) * nl * nl);
  return 0.5 / max(gv + gl, 1e-6);
}
float ggx(float a, float nh) {
  float a2 = a * a;
  return a2 / (PI * sq(nh * nh * (a2 - 1.0) + 1.0));
}
vec3 to_srgb(vec3 c) {
  return mix(pow(c, vec3(0.41666)) * 1.055 - vec3(0.055), c * 12.92, vec3(lessThanEqual(c, vec3(0.0031308))));
}
// The tangent frame of the UV mapping from screen-space derivatives (Schueler 2013), for files
// without TANGENT.
mat3 derivative_frame(vec3 eye_pos, vec3 n, vec2 uv) {
  vec3 q0 = dFdx(eye_pos), q1 = dFdy(eye_pos);
  vec2 st0 = dFdx(uv), st1 = dFdy(uv);
  vec3 q1perp = cross(q1, n), q0perp = cross(n, q0);
  vec3 t = q1perp * st0.x + q0perp * st1.x;
  vec3 b = q1perp * st0.y + q0perp * st1.y;
  float det = max(dot(t, t), dot(b, b));
  float s = det == 0.0 ? 0.0 : inversesqrt(det);
  return mat3(t * s, b * s, n);
}

void main() {
  vec4 albedo = u_base_color * v_col;
  if (u_has_base_map) albedo *= texture(u_base_map, v_uv);  // an sRGB texture: decoded to linear
  if (u_mask && albedo.a < u_cutoff) discard;
  float alpha = u_blend ? albedo.a : 1.0;
  if (!u_lit) {
    gl_FragColor = vec4(to_srgb(albedo.rgb), alpha);
    return;
  }
  // 1. Normal: interpolated (flipped on back faces of double-sided materials) or flat; the normal map.
  float face = gl_FrontFacing ? 1.0 : -1.0;
  vec3 normal;
  if (u_has_normals) {
    normal = normalize(v_nrm);
    if (u_double_sided) normal *= face;
  } else {
    normal = normalize(cross(dFdx(v_view_pos), dFdy(v_view_pos)));
  }
  vec3 geometric = normal;
  if (u_has_normal_map) {
    mat3 tbn = u_has_tangents ? mat3(normalize(v_tan), normalize(v_bit), normal) : derivative_frame(-v_view_pos, normal, v_uv);
    if (u_double_sided) tbn[0] *= face, tbn[1] *= face;
    vec3 m = texture(u_normal_map, v_uv).xyz * 2.0 - 1.0;
    // Without tangents the derivative frame's bitangent runs against glTF's +v (three.js flips it).
    m.xy *= vec2(u_normal_scale, u_has_tangents ? u_normal_scale : -u_normal_scale);
    normal = normalize(tbn * m);
  }
  // 2. Material: factors x the metallic-roughness texture (B metallic, G roughness); roughness
  //    widened where the geometric normal varies within a pixel.
  float metallic = u_metallic, rough = u_roughness;
  if (u_has_mr_map) {
    vec4 mr = texture(u_mr_map, v_uv);
    rough *= mr.g;
    metallic *= mr.b;
  }
  vec3 dxy = max(abs(dFdx(geometric)), abs(dFdy(geometric)));
  float roughness = min(max(rough, 0.045) + max(max(dxy.x, dxy.y), dxy.z), 1.0);
  vec3 diffuse = albedo.rgb * (1.0 - metallic);
  vec3 f0 = vec3(0.04), f0_blended = mix(f0, albedo.rgb, metallic);
  vec3 view = normalize(v_view_pos);
  float nv = clamp(dot(normal, view), 0.0, 1.0);
  vec2 dfg = texture(u_dfg, vec2(roughness, nv)).rg;
  vec3 compensation = 1.0 + f0_blended * (1.0 / (dfg.x + dfg.y) - 1.0);
  // 3. The headlight (eye space +z, towards the eye).
  vec3 light = vec3(0.0, 0.0, 1.0);
  vec3 h = normalize(light + view);
  float nl = clamp(dot(normal, light), 0.0, 1.0), nh = clamp(dot(normal, h), 0.0, 1.0), vh = clamp(dot(view, h), 0.0, 1.0);
  float a = sq(max(roughness, 0.045));
  vec3 irradiance = vec3(nl * u_dir_irradiance);
  vec3 color = irradiance * fresnel(f0_blended, 1.0, vh) * (smith_visibility(a, nl, nv) * ggx(a, nh)) * compensation;
  color += irradiance * diffuse / PI * (1.0 - fresnel(f0, 1.0, vh));
  // 4. Ambient light: diffuse less what single and multiple specular scattering take.
  vec3 single = f0 * dfg.x + dfg.y;
  float ess = dfg.x + dfg.y;
  vec3 favg = f0 + (1.0 - f0) / 21.0;
  vec3 multi = single * favg / (1.0 - (1.0 - ess) * favg) * (1.0 - ess);
  // Occlusion darkens the ambient light only (glTF 2.0 3.9.4; three.js's aoMap on indirect diffuse).
  float occlusion = u_has_ao_map ? (texture(u_ao_map, v_uv).r - 1.0) * u_ao_strength + 1.0 : 1.0;
  color += vec3(u_ambient_irradiance) * diffuse / PI * (1.0 - single - multi) * occlusion;
  // 5. Emission: factor x the sRGB emissive texture, added to what is reflected.
  vec3 emissive = u_emissive;
  if (u_has_emissive_map) emissive *= texture(u_emissive_map, v_uv).rgb;
  color += emissive;
  gl_FragColor = vec4(to_srgb(color), alpha);
}
)";

// Radical inverse in base 2 (Hammersley points).
float radical_inverse(std::uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return static_cast<float>(bits) * 2.3283064365386963e-10f;
}

}  // namespace

std::vector<float> dfg_table(int n, int samples) {
  std::vector<float> out(static_cast<std::size_t>(n * n * 2));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double roughness = (i + 0.5) / n, nv = (j + 0.5) / n, a = roughness * roughness, a2 = a * a;
      const double vx = std::sqrt(1 - nv * nv), vz = nv;  // view in the x-z plane, normal +z
      double scale = 0, bias = 0;
      for (int k = 0; k < samples; ++k) {
        // GGX-distributed half vector.
        const double u1 = (k + 0.5) / samples, u2 = radical_inverse(static_cast<std::uint32_t>(k));
        const double cos_h = std::sqrt((1 - u1) / (1 + (a2 - 1) * u1)), sin_h = std::sqrt(1 - cos_h * cos_h);
        const double phi = 2 * 3.14159265358979323846 * u2;
        const double hx = sin_h * std::cos(phi), hz = cos_h;
        const double vh = vx * hx + vz * hz;
        const double lz = 2 * vh * hz - vz;  // reflect the view about h
        if (lz <= 0 || vh <= 0) continue;
        const double nl = lz, nh = cos_h;
        const double gv = nl * std::sqrt(a2 + (1 - a2) * nv * nv), gl = nv * std::sqrt(a2 + (1 - a2) * nl * nl);
        const double vis = 0.5 / (gv + gl);
        const double weight = vis * 4 * nl * vh / nh;  // the BRDF over the sampling density, times N.L
        const double fc = std::pow(1 - vh, 5);
        scale += (1 - fc) * weight;
        bias += fc * weight;
      }
      out[static_cast<std::size_t>(2 * (j * n + i))] = static_cast<float>(scale / samples);
      out[static_cast<std::size_t>(2 * (j * n + i) + 1)] = static_cast<float>(bias / samples);
    }
  return out;
}

struct EngineDrawer::Impl {
  GLuint program = 0, dfg = 0;
  const EngineScene* scene = nullptr;
  std::vector<GLuint> srgb, linear;  // per image: as a base colour (sRGB) and as a normal map
  GLint min_filter = GL_LINEAR_MIPMAP_LINEAR;  // of the colour and normal textures, per draw
  GLint loc(const char* name) const { return glGetUniformLocation(program, name); }
  void free_textures() {
    if (!srgb.empty()) glDeleteTextures(static_cast<GLsizei>(srgb.size()), srgb.data());
    if (!linear.empty()) glDeleteTextures(static_cast<GLsizei>(linear.size()), linear.data());
    srgb.clear();
    linear.clear();
  }
  void draw_primitive(const EnginePrimitive& p, const EngineMaterial& mat);
};

namespace {

enum Attribute : GLuint { kPos = 0, kNrm = 1, kTan = 2, kUv = 3, kCol = 4 };

GLuint upload(const Image& img, GLint internal_format) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, internal_format, img.width, img.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
  // A file's own mip levels (KTX2) as an engine uploads them; else made as WebGL engines make
  // them for a PNG (glTF samplers ask for trilinear).
  for (std::size_t k = 0; k < img.mips.size(); ++k)
    glTexImage2D(GL_TEXTURE_2D, static_cast<GLint>(k + 1), internal_format, img.mips[k].width, img.mips[k].height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, img.mips[k].rgba.data());
  if (img.mips.empty()) glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace

EngineDrawer::EngineDrawer() : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.program = glCreateProgram();
  const GLuint vs = compile_shader(GL_VERTEX_SHADER, kVertexShader, "engine method"), fs = compile_shader(GL_FRAGMENT_SHADER, kFragmentShader, "engine method");
  glAttachShader(m.program, vs);
  glAttachShader(m.program, fs);
  glBindAttribLocation(m.program, kPos, "a_pos");
  glBindAttribLocation(m.program, kNrm, "a_nrm");
  glBindAttribLocation(m.program, kTan, "a_tan");
  glBindAttribLocation(m.program, kUv, "a_uv");
  glBindAttribLocation(m.program, kCol, "a_col");
  glLinkProgram(m.program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(m.program, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("engine method: the shader program does not link");
  const std::vector<float> table = dfg_table(kDfgSide, 1024);
  glGenTextures(1, &m.dfg);
  glBindTexture(GL_TEXTURE_2D, m.dfg);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, kDfgSide, kDfgSide, 0, GL_RG, GL_FLOAT, table.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

EngineDrawer::~EngineDrawer() {
  impl_->free_textures();
  glDeleteTextures(1, &impl_->dfg);
  glDeleteProgram(impl_->program);
}

void EngineDrawer::set_scene(const EngineScene& scene) {
  impl_->free_textures();
  impl_->scene = &scene;
  for (const Image& img : scene.images) {
    impl_->srgb.push_back(upload(img, GL_SRGB8_ALPHA8));
    impl_->linear.push_back(upload(img, GL_RGBA8));
  }
}

void EngineDrawer::Impl::draw_primitive(const EnginePrimitive& p, const EngineMaterial& mat) {
  const bool lit = p.mode == EnginePrimitive::Mode::kTriangles;  // lines and points: unlit materials
  glUniform4fv(loc("u_base_color"), 1, mat.base_color.data());
  glUniform1f(loc("u_metallic"), mat.metallic);
  glUniform1f(loc("u_roughness"), mat.roughness);
  glUniform1f(loc("u_normal_scale"), mat.normal_scale);
  glUniform1f(loc("u_cutoff"), mat.alpha_cutoff);
  glUniform1i(loc("u_lit"), lit);
  glUniform1i(loc("u_mask"), mat.alpha == EngineMaterial::Alpha::kMask);
  glUniform1i(loc("u_blend"), mat.alpha == EngineMaterial::Alpha::kBlend);
  glUniform1i(loc("u_double_sided"), mat.double_sided);
  const bool base_map = mat.base_texture >= 0 && !p.uvs.empty(), normal_map = lit && mat.normal_texture >= 0 && !p.uvs.empty();
  glUniform1i(loc("u_has_base_map"), base_map);
  glUniform1i(loc("u_has_normal_map"), normal_map);
  glUniform1i(loc("u_has_normals"), !p.normals.empty());
  glUniform1i(loc("u_has_tangents"), !p.tangents.empty());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, base_map ? srgb[static_cast<std::size_t>(mat.base_texture)] : 0);
  // Wraps are the material's sampler's (images may be shared by textures with other samplers).
  if (base_map) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, min_filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, mat.base_wrap_s);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, mat.base_wrap_t);
  }
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, normal_map ? linear[static_cast<std::size_t>(mat.normal_texture)] : 0);
  if (normal_map) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, min_filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, mat.normal_wrap_s);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, mat.normal_wrap_t);
  }
  // The other channels' textures: units 3 (metallic-roughness), 4 (occlusion), 5 (emission).
  const bool mr_map = lit && mat.metal_rough_texture >= 0 && !p.uvs.empty();
  const bool ao_map = lit && mat.occlusion_texture >= 0 && !p.uvs.empty();
  const bool emissive_map = lit && mat.emissive_texture >= 0 && !p.uvs.empty();
  glUniform1i(loc("u_has_mr_map"), mr_map);
  glUniform1i(loc("u_has_ao_map"), ao_map);
  glUniform1i(loc("u_has_emissive_map"), emissive_map);
  glUniform1f(loc("u_ao_strength"), mat.occlusion_strength);
  glUniform3fv(loc("u_emissive"), 1, mat.emissive.data());
  struct Map {
    bool on;
    GLenum unit;
    const std::vector<GLuint>* images;
    int image, wrap_s, wrap_t;
  };
  const Map maps[3] = {{mr_map, GL_TEXTURE3, &linear, mat.metal_rough_texture, mat.metal_rough_wrap_s, mat.metal_rough_wrap_t},
                       {ao_map, GL_TEXTURE4, &linear, mat.occlusion_texture, mat.occlusion_wrap_s, mat.occlusion_wrap_t},
                       {emissive_map, GL_TEXTURE5, &srgb, mat.emissive_texture, mat.emissive_wrap_s, mat.emissive_wrap_t}};
  for (const Map& map : maps) {
    glActiveTexture(map.unit);
    glBindTexture(GL_TEXTURE_2D, map.on ? (*map.images)[static_cast<std::size_t>(map.image)] : 0);
    if (map.on) {
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, map.wrap_s);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, map.wrap_t);
    }
  }
  glActiveTexture(GL_TEXTURE0);
  if (mat.double_sided || !lit) glDisable(GL_CULL_FACE);
  else glEnable(GL_CULL_FACE);
  // Attributes the primitive lacks take constants: white vertex colours, and unused defaults.
  auto array = [](GLuint index, int size, const std::vector<float>& data, std::initializer_list<float> fallback) {
    if (data.empty()) {
      glDisableVertexAttribArray(index);
      const float* f = fallback.begin();
      glVertexAttrib4f(index, f[0], f[1], f[2], f[3]);
    } else {
      glEnableVertexAttribArray(index);
      glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, 0, data.data());
    }
  };
  array(kPos, 3, p.positions, {0, 0, 0, 1});
  array(kNrm, 3, p.normals, {0, 0, 1, 0});
  array(kTan, 4, p.tangents, {1, 0, 0, 1});
  array(kUv, 2, p.uvs, {0, 0, 0, 0});
  array(kCol, 4, p.colors, {1, 1, 1, 1});
  const GLenum mode = p.mode == EnginePrimitive::Mode::kLines ? GL_LINES : p.mode == EnginePrimitive::Mode::kPoints ? GL_POINTS : GL_TRIANGLES;
  glDrawElements(mode, static_cast<GLsizei>(p.indices.size()), GL_UNSIGNED_INT, p.indices.data());
}

std::size_t EngineDrawer::draw(const Camera& camera, const EngineLights& lights, const std::optional<std::string>& alpha_mode,
                               float alpha_cutoff, bool mipmaps) {
  Impl& m = *impl_;
  if (!m.scene) return 0;
  m.min_filter = mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR;
  std::size_t drawn = 0;
  auto material_of = [&](const EnginePrimitive& p) {
    EngineMaterial mat = p.material;
    if (p.mode != EnginePrimitive::Mode::kTriangles) return mat;
    if (alpha_mode)
      mat.alpha = *alpha_mode == "MASK" ? EngineMaterial::Alpha::kMask : *alpha_mode == "BLEND" ? EngineMaterial::Alpha::kBlend : EngineMaterial::Alpha::kOpaque;
    if (alpha_cutoff >= 0) mat.alpha_cutoff = alpha_cutoff;
    return mat;
  };
  glUseProgram(m.program);
  glUniformMatrix4fv(m.loc("u_view"), 1, GL_FALSE, camera.view().data());
  glUniformMatrix4fv(m.loc("u_proj"), 1, GL_FALSE, camera.projection().data());
  glUniform1f(m.loc("u_dir_irradiance"), lights.directional);
  glUniform1f(m.loc("u_ambient_irradiance"), lights.ambient);
  glUniform1i(m.loc("u_base_map"), 0);
  glUniform1i(m.loc("u_normal_map"), 1);
  glUniform1i(m.loc("u_dfg"), 2);
  glUniform1i(m.loc("u_mr_map"), 3);
  glUniform1i(m.loc("u_ao_map"), 4);
  glUniform1i(m.loc("u_emissive_map"), 5);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, m.dfg);
  glActiveTexture(GL_TEXTURE0);
  glDisable(GL_LIGHTING);
  glDisable(GL_ALPHA_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glPointSize(1);
  glLineWidth(1);
  // Opaque and masked first, then blended without depth writes, each in file order (engines sort
  // objects, not the primitives of one mesh).
  for (int pass = 0; pass < 2; ++pass) {
    const bool blend_pass = pass == 1;
    glDepthMask(blend_pass ? GL_FALSE : GL_TRUE);
    if (blend_pass) glEnable(GL_BLEND), glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    else glDisable(GL_BLEND);
    for (const EnginePrimitive& p : m.scene->primitives) {
      const EngineMaterial mat = material_of(p);
      if ((mat.alpha == EngineMaterial::Alpha::kBlend) == blend_pass) m.draw_primitive(p, mat), ++drawn;
    }
  }
  for (GLuint a : {kPos, kNrm, kTan, kUv, kCol}) glDisableVertexAttribArray(a);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);
  glUseProgram(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  return drawn;
}

}  // namespace qf::render
