// Loading scenes for runtime_gl: .glb/.gltf through tinygltf (the one runtime file that includes
// it). References made from input files are tools/reference_scene.
#include "runtime_gl/loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <type_traits>

#include "core/color.h"
#include "core/error.h"
#include "core/gltf_keys.h"

namespace qf::render {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& code, const std::string& detail) {
  throw InputError("render.gltf." + code, path, "", detail);
}

// Reads an accessor as floats (`components` per element) or as indices, honouring byteStride.
struct AccessorReader {
  const tinygltf::Model& m;
  const std::string& path;

  // The accessor `index` names, or a clear error when it names none.
  const tinygltf::Accessor& accessor(int index) const {
    if (index < 0 || index >= static_cast<int>(m.accessors.size()))
      fail(path, "accessor", "accessor " + std::to_string(index) + " does not exist (" + std::to_string(m.accessors.size()) + " accessors)");
    return m.accessors[static_cast<std::size_t>(index)];
  }

  const unsigned char* base(const tinygltf::Accessor& a, std::size_t elem_size, std::size_t& stride) const {
    if (a.bufferView < 0 || a.bufferView >= static_cast<int>(m.bufferViews.size())) fail(path, "accessor", "accessor without a valid bufferView");
    const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (v.buffer < 0 || v.buffer >= static_cast<int>(m.buffers.size()))
      fail(path, "accessor", "bufferView " + std::to_string(a.bufferView) + " names buffer " + std::to_string(v.buffer) + ", which does not exist");
    const tinygltf::Buffer& b = m.buffers[static_cast<std::size_t>(v.buffer)];
    stride = v.byteStride ? v.byteStride : elem_size;
    // In this order so that no product wraps: a count the buffer cannot hold fails before it is multiplied.
    const std::size_t start = a.byteOffset + v.byteOffset;
    if (start > b.data.size() || (a.count && ((a.count - 1) > (b.data.size() - start) / std::max<std::size_t>(stride, 1) ||
                                              (a.count - 1) * stride + elem_size > b.data.size() - start)))
      fail(path, "accessor", "accessor reaches past the end of its buffer");
    return b.data.data() + v.byteOffset + a.byteOffset;
  }

  std::vector<float> floats(int index, int components) const {
    const tinygltf::Accessor& a = accessor(index);
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || tinygltf::GetNumComponentsInType(a.type) != components)
      fail(path, "accessor", "expected a float accessor with " + std::to_string(components) + " components");
    std::size_t stride = 0;
    const unsigned char* p = base(a, sizeof(float) * static_cast<std::size_t>(components), stride);
    std::vector<float> out(a.count * static_cast<std::size_t>(components));
    for (std::size_t i = 0; i < a.count; ++i)
      std::memcpy(&out[i * static_cast<std::size_t>(components)], p + i * stride, sizeof(float) * static_cast<std::size_t>(components));
    return out;
  }

  std::vector<std::uint32_t> indices(int index) const {
    const tinygltf::Accessor& a = accessor(index);
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    if (a.type != TINYGLTF_TYPE_SCALAR || (size != 1 && size != 2 && size != 4)) fail(path, "accessor", "bad index accessor");
    std::size_t stride = 0;
    const unsigned char* p = base(a, static_cast<std::size_t>(size), stride);
    std::vector<std::uint32_t> out(a.count);
    for (std::size_t i = 0; i < a.count; ++i) {
      std::uint32_t v = 0;
      std::memcpy(&v, p + i * stride, static_cast<std::size_t>(size));  // little-endian host
      out[i] = v;
    }
    return out;
  }
};

// A number of an extension as the integer type T (int or uint32_t, exact in a double), or a clear
// error when T cannot hold it: casting an out-of-range or NaN double is undefined (found by the glb
// fuzz target).
template <class T>
T to_integer(double d, const std::string& path, const char* key) {
  static_assert(std::is_integral_v<T> && sizeof(T) <= 4, "bounds must be exact in a double");
  if (!(d >= static_cast<double>(std::numeric_limits<T>::lowest()) && d <= static_cast<double>(std::numeric_limits<T>::max())))
    fail(path, "extension", std::string(key) + ": " + std::to_string(d) + " is out of range");
  return static_cast<T>(d);
}

template <class T>
std::vector<T> number_array(const tinygltf::Value& ext, const char* key, const std::string& path) {
  std::vector<T> out;
  if (!ext.Has(key)) return out;
  const tinygltf::Value& a = ext.Get(key);
  for (std::size_t i = 0; i < a.ArrayLen(); ++i) {
    const double d = a.Get(static_cast<int>(i)).GetNumberAsDouble();
    if constexpr (std::is_integral_v<T>) out.push_back(to_integer<T>(d, path, key));
    else out.push_back(static_cast<T>(d));
  }
  return out;
}

Image to_image(const tinygltf::Image& img, const std::string& path) {
  if (img.bits != 8 || (img.component != 3 && img.component != 4) || img.width <= 0 || img.height <= 0)
    fail(path, "image", "image '" + img.name + "' is not an 8-bit RGB or RGBA image");
  Image out;
  out.width = img.width;
  out.height = img.height;
  const std::size_t n = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height);
  out.rgba.resize(n * 4);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c)
      out.rgba[i * 4 + c] = c < img.component ? img.image[i * static_cast<std::size_t>(img.component) + c] : 255;
  return out;
}

// A 1x1 white texture for materials without a base colour texture.
Image white_image() { return Image{1, 1, {255, 255, 255, 255}}; }


// tinygltf 2.7.0 hands an image's bufferView to stb_image without checking that it lies within its
// buffer (a crafted byteLength read past the end, found by the glb fuzz target): this image loader
// checks the view first (tinygltf has checked that the view and its buffer exist), then decodes with
// tinygltf's own stb_image loader and its default options (user data null: RGBA, as before).
bool load_image_checked(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int width,
                        int height, const unsigned char* bytes, int size, void* user) {
  if (image->bufferView >= 0) {
    const tinygltf::Model& m = *static_cast<const tinygltf::Model*>(user);
    const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(image->bufferView));
    const std::size_t buffer = m.buffers.at(static_cast<std::size_t>(v.buffer)).data.size();
    if (v.byteOffset > buffer || v.byteLength > buffer - v.byteOffset || size < 0 ||
        static_cast<std::size_t>(size) != v.byteLength) {
      if (err) *err += "image[" + std::to_string(index) + "] bufferView reaches past the end of its buffer";
      return false;
    }
  }
  return tinygltf::LoadImageData(image, index, err, warn, width, height, bytes, size, nullptr);
}

tinygltf::Model read_gltf(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError("file.unreadable", path, "", "cannot open: no such file");
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&load_image_checked, &m);
  std::string err, warn;
  const bool binary = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  const bool ok = binary ? loader.LoadBinaryFromFile(&m, &err, &warn, path) : loader.LoadASCIIFromFile(&m, &err, &warn, path);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    std::ifstream raw(path, std::ios::binary);
    const std::string head(std::istreambuf_iterator<char>(raw), {});
    if (head.find("KHR_draco_mesh_compression") != std::string::npos)
      fail(path, "draco", "requires KHR_draco_mesh_compression, which qf-render does not decode; render the uncompressed .glb");
    fail(path, "parse", err.empty() ? "not a readable glTF file" : err);
  }
  return m;
}

// COLOR_0 as the baker writes it (normalized 16-bit linear RGBA) -> sRGB bytes; the base colour
// when absent.
std::vector<Rgb8> read_colors(const AccessorReader& read, const tinygltf::Primitive& prim, std::size_t n) {
  const auto col = prim.attributes.find("COLOR_0");
  if (col == prim.attributes.end()) return std::vector<Rgb8>(n, kBaseColor);
  const tinygltf::Accessor& a = read.accessor(col->second);
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT || a.type != TINYGLTF_TYPE_VEC4 || a.count != n)
    fail(read.path, "colors", "COLOR_0 must be normalized unsigned short RGBA, one per vertex");
  std::size_t stride = 0;
  const unsigned char* b = read.base(a, 8, stride);
  std::vector<Rgb8> out;
  for (std::size_t i = 0; i < a.count; ++i) {
    std::uint16_t c[4];
    std::memcpy(c, b + i * stride, 8);
    out.push_back({linear16_to_srgb(c[0]), linear16_to_srgb(c[1]), linear16_to_srgb(c[2])});
  }
  return out;
}

std::vector<Vec3f> read_vec3(const AccessorReader& read, const tinygltf::Primitive& prim, const char* name) {
  std::vector<Vec3f> out;
  const auto it = prim.attributes.find(name);
  if (it == prim.attributes.end()) return out;
  const std::vector<float> f = read.floats(it->second, 3);
  for (std::size_t i = 0; i + 2 < f.size(); i += 3) out.push_back({f[i], f[i + 1], f[i + 2]});
  return out;
}

PointImpostorScene point_scene(const tinygltf::Model& m, const std::string& path) {
  PointImpostorScene s;
  s.pixel = static_cast<float>(m.extensions.at(kPointExtension).Get("pixelSize").GetNumberAsDouble());
  if (!(s.pixel > 0)) fail(path, "points", std::string(kPointExtension) + ".pixelSize must be positive");
  AccessorReader read{m, path};
  for (const tinygltf::Mesh& mesh : m.meshes)
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      if (prim.mode != TINYGLTF_MODE_POINTS || !s.positions.empty()) continue;
      s.positions = read_vec3(read, prim, "POSITION");
      s.normals = read_vec3(read, prim, "NORMAL");
      s.colors = read_colors(read, prim, s.positions.size());
    }
  if (s.positions.empty()) fail(path, "points", "has " + std::string(kPointExtension) + " but no POINTS primitive with points");
  if (!s.normals.empty() && s.normals.size() != s.positions.size()) fail(path, "points", "NORMAL and POSITION counts differ");
  if (s.normals.empty()) s.normals.assign(s.positions.size(), Vec3f{0, 0, 1});
  for (Vec3f q : s.positions) s.bounds.add(q);
  return s;
}

ClusterScene cluster_scene(const tinygltf::Model& m, const std::string& path) {
  ClusterScene s;
  s.cell = static_cast<float>(m.nodes[0].extras.Get(kCellWidthExtra).GetNumberAsDouble());
  AccessorReader read{m, path};
  for (const tinygltf::Mesh& mesh : m.meshes)
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      const std::vector<Vec3f> pos = read_vec3(read, prim, "POSITION");
      const std::vector<Rgb8> col = read_colors(read, prim, pos.size());
      if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
        std::vector<Vec3f> nrm = read_vec3(read, prim, "NORMAL");
        if (nrm.size() != pos.size()) fail(path, "mesh", "cluster LOD triangles need one NORMAL per vertex");
        const auto base = static_cast<std::uint32_t>(s.mesh.positions.size());
        for (std::size_t i = 0; i < pos.size(); ++i) s.mesh.indices.push_back(base + static_cast<std::uint32_t>(i));
        s.mesh.positions.insert(s.mesh.positions.end(), pos.begin(), pos.end());
        s.mesh.normals.insert(s.mesh.normals.end(), nrm.begin(), nrm.end());
        s.mesh.colors.insert(s.mesh.colors.end(), col.begin(), col.end());
      } else if (prim.mode == TINYGLTF_MODE_LINE) {
        const auto th = prim.attributes.find(kThicknessAttribute);
        if (th == prim.attributes.end()) fail(path, "lines", "cluster LOD lines need _THICKNESS");
        const std::vector<float> t = read.floats(th->second, 1);
        if (t.size() != pos.size() || pos.size() % 2) fail(path, "lines", "_THICKNESS needs one value per line vertex");
        s.line_positions.insert(s.line_positions.end(), pos.begin(), pos.end());
        s.line_colors.insert(s.line_colors.end(), col.begin(), col.end());
        for (std::size_t i = 0; i < t.size(); i += 2) s.thickness.push_back(t[i]);
      } else if (prim.mode == TINYGLTF_MODE_POINTS) {
        s.points.insert(s.points.end(), pos.begin(), pos.end());
        s.point_colors.insert(s.point_colors.end(), col.begin(), col.end());
      }
    }
  for (const auto* v : {&s.mesh.positions, &s.line_positions, &s.points})
    for (Vec3f q : *v) s.bounds.add(q);
  s.mesh.bounds = s.bounds;
  if (s.bounds.empty()) fail(path, "mesh", "a cluster LOD without geometry");
  return s;
}

// The impostor level of the file (or of its mesh `only_mesh` alone, >= 0).
ImpostorScene impostor_scene(const tinygltf::Model& m, const std::string& path, int only_mesh = -1);

// --- the engine's view of a file ---------------------------------------------------------------

// A vertex attribute as floats, `components` per vertex: FLOAT, or normalized UNSIGNED_BYTE /
// UNSIGNED_SHORT (glTF 2.0 3.7.2.1 allows these for COLOR_n and TEXCOORD_n). VEC3 colours get
// alpha 1 when `components` is 4.
std::vector<float> attribute_floats(const AccessorReader& read, int index, int components) {
  const tinygltf::Accessor& a = read.accessor(index);
  const int have = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && have == components) return read.floats(index, components);
  const int size = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? 1 : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2 : 0;
  const bool colour_rgb = components == 4 && have == 3;
  if (!(have == components || colour_rgb) || (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && (size == 0 || !a.normalized)))
    fail(read.path, "accessor", "accessor " + std::to_string(index) + ": expected " + std::to_string(components) +
                                    " float or normalized unsigned components");
  const std::size_t elem = static_cast<std::size_t>(have) * (size ? static_cast<std::size_t>(size) : 4);
  std::size_t stride = 0;
  const unsigned char* p = read.base(a, elem, stride);
  std::vector<float> out;
  out.reserve(a.count * static_cast<std::size_t>(components));
  for (std::size_t i = 0; i < a.count; ++i) {
    for (int c = 0; c < have; ++c) {
      const unsigned char* q = p + i * stride + static_cast<std::size_t>(c) * (size ? static_cast<std::size_t>(size) : 4);
      float v = 0;
      if (size == 1) v = *q / 255.0f;
      else if (size == 2) {
        std::uint16_t u = 0;
        std::memcpy(&u, q, 2);
        v = u / 65535.0f;
      } else {
        std::memcpy(&v, q, 4);
      }
      out.push_back(v);
    }
    if (colour_rgb) out.push_back(1.0f);
  }
  return out;
}

using Mat4d = std::array<double, 16>;  // column-major, as glTF stores node matrices

Mat4d multiply(const Mat4d& a, const Mat4d& b) {
  Mat4d r{};
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr)
      for (int k = 0; k < 4; ++k) r[static_cast<std::size_t>(c * 4 + rr)] += a[static_cast<std::size_t>(k * 4 + rr)] * b[static_cast<std::size_t>(c * 4 + k)];
  return r;
}

// A node's local transform: its matrix, else T * R * S (glTF 2.0 3.5.3).
Mat4d local_transform(const tinygltf::Node& n) {
  Mat4d m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (n.matrix.size() == 16) {
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    return m;
  }
  const double x = n.rotation.size() == 4 ? n.rotation[0] : 0, y = n.rotation.size() == 4 ? n.rotation[1] : 0,
               z = n.rotation.size() == 4 ? n.rotation[2] : 0, w = n.rotation.size() == 4 ? n.rotation[3] : 1;
  const double sx = n.scale.size() == 3 ? n.scale[0] : 1, sy = n.scale.size() == 3 ? n.scale[1] : 1, sz = n.scale.size() == 3 ? n.scale[2] : 1;
  const Mat4d r{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
                2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
                2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0,
                0, 0, 0, 1};
  for (int k = 0; k < 4; ++k) {
    m[static_cast<std::size_t>(k)] = r[static_cast<std::size_t>(k)] * sx;
    m[static_cast<std::size_t>(4 + k)] = r[static_cast<std::size_t>(4 + k)] * sy;
    m[static_cast<std::size_t>(8 + k)] = r[static_cast<std::size_t>(8 + k)] * sz;
  }
  if (n.translation.size() == 3) m[12] = n.translation[0], m[13] = n.translation[1], m[14] = n.translation[2];
  return m;
}

EngineMaterial engine_material(const tinygltf::Model& m, int index, int& uv_set) {
  EngineMaterial out;  // glTF's default material
  uv_set = 0;
  if (index < 0 || index >= static_cast<int>(m.materials.size())) return out;
  const tinygltf::Material& mat = m.materials[static_cast<std::size_t>(index)];
  const tinygltf::PbrMetallicRoughness& pbr = mat.pbrMetallicRoughness;
  for (std::size_t c = 0; c < 4 && c < pbr.baseColorFactor.size(); ++c) out.base_color[c] = static_cast<float>(pbr.baseColorFactor[c]);
  auto image_of = [&](int texture) {
    if (texture < 0 || texture >= static_cast<int>(m.textures.size())) return -1;
    const int src = m.textures[static_cast<std::size_t>(texture)].source;
    return src >= 0 && src < static_cast<int>(m.images.size()) ? src : -1;
  };
  out.base_texture = image_of(pbr.baseColorTexture.index);
  if (out.base_texture >= 0) uv_set = pbr.baseColorTexture.texCoord;
  out.metallic = static_cast<float>(pbr.metallicFactor);
  out.roughness = static_cast<float>(pbr.roughnessFactor);
  out.normal_texture = image_of(mat.normalTexture.index);
  out.normal_scale = static_cast<float>(mat.normalTexture.scale);
  out.alpha = mat.alphaMode == "MASK" ? EngineMaterial::Alpha::kMask : mat.alphaMode == "BLEND" ? EngineMaterial::Alpha::kBlend : EngineMaterial::Alpha::kOpaque;
  out.alpha_cutoff = static_cast<float>(mat.alphaCutoff);
  out.double_sided = mat.doubleSided;
  return out;
}

// One primitive of a mesh, placed by `world`.
EnginePrimitive engine_primitive(const AccessorReader& read, const tinygltf::Primitive& prim, const Mat4d& world) {
  EnginePrimitive p;
  if (prim.mode == TINYGLTF_MODE_LINE) p.mode = EnginePrimitive::Mode::kLines;
  else if (prim.mode == TINYGLTF_MODE_POINTS) p.mode = EnginePrimitive::Mode::kPoints;
  int uv_set = 0;
  p.material = engine_material(read.m, prim.material, uv_set);
  auto attribute = [&](const std::string& name, int components) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? std::vector<float>() : attribute_floats(read, it->second, components);
  };
  p.positions = attribute("POSITION", 3);
  const std::size_t n = p.positions.size() / 3;
  p.normals = attribute("NORMAL", 3);
  p.tangents = attribute("TANGENT", 4);
  p.uvs = attribute("TEXCOORD_" + std::to_string(uv_set), 2);
  p.colors = attribute("COLOR_0", 4);
  if ((!p.normals.empty() && p.normals.size() != n * 3) || (!p.tangents.empty() && p.tangents.size() != n * 4) ||
      (!p.uvs.empty() && p.uvs.size() != n * 2) || (!p.colors.empty() && p.colors.size() != n * 4))
    fail(read.path, "mesh", "a primitive's attributes differ in count from POSITION");
  if (prim.indices >= 0) {
    p.indices = read.indices(prim.indices);
    for (std::uint32_t i : p.indices)
      if (i >= n) fail(read.path, "mesh", "index " + std::to_string(i) + " out of range (" + std::to_string(n) + " vertices)");
  } else {
    for (std::uint32_t i = 0; i < n; ++i) p.indices.push_back(i);
  }
  // World space: points by the matrix, normals by its inverse transpose (the cofactor matrix,
  // normalised), tangents by the matrix; a negative determinant mirrors, so flip the winding.
  const Mat4d& w = world;
  auto at = [&](int r, int c) { return w[static_cast<std::size_t>(c * 4 + r)]; };
  const double det = at(0, 0) * (at(1, 1) * at(2, 2) - at(1, 2) * at(2, 1)) - at(0, 1) * (at(1, 0) * at(2, 2) - at(1, 2) * at(2, 0)) +
                     at(0, 2) * (at(1, 0) * at(2, 1) - at(1, 1) * at(2, 0));
  for (std::size_t v = 0; v < n; ++v) {
    const double x = p.positions[v * 3], y = p.positions[v * 3 + 1], z = p.positions[v * 3 + 2];
    for (int r = 0; r < 3; ++r) p.positions[v * 3 + static_cast<std::size_t>(r)] = static_cast<float>(at(r, 0) * x + at(r, 1) * y + at(r, 2) * z + at(r, 3));
  }
  auto cof = [&](int r, int c) {  // cofactor of the 3x3 part
    const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
    return at(r1, c1) * at(r2, c2) - at(r1, c2) * at(r2, c1);
  };
  // Directions (xyz of every `stride` floats) through a 3x3 matrix m(r, c), renormalised.
  auto turn = [](std::vector<float>& d, std::size_t stride, auto&& m) {
    for (std::size_t v = 0; v + 2 < d.size(); v += stride) {
      const Vec3f q{d[v], d[v + 1], d[v + 2]};
      Vec3f t;
      for (int r = 0; r < 3; ++r) t[r] = static_cast<float>(m(r, 0) * q.x + m(r, 1) * q.y + m(r, 2) * q.z);
      t = normalized(t);
      std::copy_n(&t.x, 3, &d[v]);
    }
  };
  turn(p.normals, 3, cof);
  turn(p.tangents, 4, at);
  if (det < 0 && p.mode == EnginePrimitive::Mode::kTriangles)
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) std::swap(p.indices[t + 1], p.indices[t + 2]);
  return p;
}

// The root nodes of the default scene (scene 0 when none is named; none when there are no scenes).
std::vector<int> scene_roots(const tinygltf::Model& m) {
  const int scene = m.defaultScene >= 0 ? m.defaultScene : (m.scenes.empty() ? -1 : 0);
  if (scene >= 0 && scene < static_cast<int>(m.scenes.size())) return m.scenes[static_cast<std::size_t>(scene)].nodes;
  return {};
}

// The node trees under `roots`, every mesh primitive placed by its composed transform.
EngineScene engine_scene(const tinygltf::Model& m, const std::string& path, const std::vector<int>& roots) {
  EngineScene s;
  for (const tinygltf::Image& img : m.images) s.images.push_back(to_image(img, path));
  AccessorReader read{m, path};
  std::vector<int> depth(m.nodes.size(), -1);  // on the current path: a cycle guard
  const Mat4d identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  auto visit = [&](auto&& self, int node, const Mat4d& parent, int level) -> void {
    if (node < 0 || node >= static_cast<int>(m.nodes.size())) fail(path, "nodes", "node " + std::to_string(node) + " does not exist");
    if (depth[static_cast<std::size_t>(node)] >= 0) fail(path, "nodes", "nodes[" + std::to_string(node) + "] is its own ancestor (a cycle)");
    depth[static_cast<std::size_t>(node)] = level;
    const tinygltf::Node& n = m.nodes[static_cast<std::size_t>(node)];
    const Mat4d world = multiply(parent, local_transform(n));
    if (n.mesh >= 0 && n.mesh < static_cast<int>(m.meshes.size()))
      for (const tinygltf::Primitive& prim : m.meshes[static_cast<std::size_t>(n.mesh)].primitives)
        if (prim.mode == TINYGLTF_MODE_TRIANGLES || prim.mode == TINYGLTF_MODE_LINE || prim.mode == TINYGLTF_MODE_POINTS)
          s.primitives.push_back(engine_primitive(read, prim, world));
    for (int child : n.children) self(self, child, world, level + 1);
    depth[static_cast<std::size_t>(node)] = -1;
  };
  for (int r : roots) visit(visit, r, identity, 0);
  for (const EnginePrimitive& p : s.primitives) {
    for (std::size_t v = 0; v + 2 < p.positions.size(); v += 3) s.bounds.add({p.positions[v], p.positions[v + 1], p.positions[v + 2]});
    for (int t : {p.material.base_texture, p.material.normal_texture})
      if (t >= static_cast<int>(s.images.size())) fail(path, "image", "a material names a missing image");
  }
  return s;
}

}  // namespace

// A combined LOD file (`qf-bake --lod-file`): the scene's one root node lists its lower LODs
// under MSFT_lod and their screen coverages in its extras. Empty when the file has none.
std::vector<int> lod_nodes(const tinygltf::Model& m, const std::vector<int>& roots, const std::string& path, std::vector<double>& coverage) {
  if (roots.size() != 1 || roots[0] < 0 || roots[0] >= static_cast<int>(m.nodes.size())) return {};
  const tinygltf::Node& root = m.nodes[static_cast<std::size_t>(roots[0])];
  const auto ext = root.extensions.find(kLodExtension);
  if (ext == root.extensions.end()) return {};
  std::vector<int> nodes{roots[0]};
  for (int id : number_array<int>(ext->second, "ids", path)) nodes.push_back(id);
  coverage = number_array<double>(root.extras, kScreenCoverageExtra, path);
  return nodes;
}

BakedScene load_baked(const std::string& path) {
  const tinygltf::Model m = read_gltf(path);  // parsed once, whatever it holds
  BakedScene s;
  const std::vector<int> roots = scene_roots(m);
  std::vector<double> coverage;
  const std::vector<int> lods = lod_nodes(m, roots, path, coverage);
  if (!lods.empty()) {
    // Each LOD alone, finest first; the file itself stands for the finest.
    for (int node : lods) {
      if (node < 0 || node >= static_cast<int>(m.nodes.size())) fail(path, "nodes", "MSFT_lod names node " + std::to_string(node) + ", which does not exist");
      BakedScene level;
      level.engine = engine_scene(m, path, {node});
      level.impostor = impostor_scene(m, path, m.nodes[static_cast<std::size_t>(node)].mesh);
      s.lods.push_back(std::move(level));
    }
    s.lod_coverage = coverage;
    s.engine = s.lods[0].engine;
    s.impostor = s.lods[0].impostor;
    return s;
  }
  s.engine = engine_scene(m, path, roots);
  if (m.extensions.count(kPointExtension)) {
    s.kind = BakedScene::kPoints;
    s.points = point_scene(m, path);
  } else if (!m.nodes.empty() && m.nodes[0].extras.Has(kCellWidthExtra)) {
    s.kind = BakedScene::kCluster;
    s.cluster = cluster_scene(m, path);
  } else {
    s.impostor = impostor_scene(m, path);
  }
  return s;
}

ImpostorScene load_gltf(const std::string& path) { return impostor_scene(read_gltf(path), path); }

namespace {

ImpostorScene impostor_scene(const tinygltf::Model& m, const std::string& path, int only_mesh) {
  ImpostorScene s;
  AccessorReader read{m, path};
  // Textures: one per glTF image, plus a white one at the end for untextured materials.
  for (const tinygltf::Image& img : m.images) s.textures.push_back(to_image(img, path));
  const auto white = static_cast<std::uint32_t>(s.textures.size());
  s.textures.push_back(white_image());
  if (!m.materials.empty()) {
    s.alpha_mode = m.materials[0].alphaMode;
    s.alpha_cutoff = static_cast<float>(m.materials[0].alphaCutoff);
    s.double_sided = m.materials[0].doubleSided;
  }

  // 1. Every triangle primitive of every mesh, expanded to flat vertex arrays; `groups` lists the
  //    items' triangles per material, in file order.
  struct Group {
    int material;
    std::vector<std::uint32_t> first;  // first vertex of each triangle
  };
  std::vector<Group> groups;
  for (std::size_t mi = 0; mi < m.meshes.size(); ++mi) {
    if (only_mesh >= 0 && mi != static_cast<std::size_t>(only_mesh)) continue;
    for (const tinygltf::Primitive& prim : m.meshes[mi].primitives) {
      if (prim.mode != TINYGLTF_MODE_TRIANGLES) continue;
      const auto pos_it = prim.attributes.find("POSITION");
      if (pos_it == prim.attributes.end()) fail(path, "mesh", "a triangle primitive has no POSITION");
      const std::vector<float> pos = read.floats(pos_it->second, 3);
      const auto uv_it = prim.attributes.find("TEXCOORD_0");
      const std::vector<float> uv = uv_it == prim.attributes.end() ? std::vector<float>() : read.floats(uv_it->second, 2);
      std::vector<std::uint32_t> idx;
      if (prim.indices >= 0) {
        idx = read.indices(prim.indices);
      } else {
        for (std::uint32_t i = 0; i < pos.size() / 3; ++i) idx.push_back(i);
      }
      Group g{prim.material, {}};
      for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
        g.first.push_back(static_cast<std::uint32_t>(s.positions.size() / 3));
        for (int c = 0; c < 3; ++c) {
          const std::size_t v = idx[t + static_cast<std::size_t>(c)];
          if (v * 3 + 2 >= pos.size()) fail(path, "mesh", "an index is past the end of POSITION");
          s.positions.insert(s.positions.end(), {pos[v * 3], pos[v * 3 + 1], pos[v * 3 + 2]});
          s.uvs.insert(s.uvs.end(), {uv.empty() ? 0.0f : uv[v * 2], uv.empty() ? 0.0f : uv[v * 2 + 1]});
          s.bounds.add({pos[v * 3], pos[v * 3 + 1], pos[v * 3 + 2]});
        }
      }
      groups.push_back(std::move(g));
    }
  }
  auto texture_of = [&](int material) -> std::uint32_t {
    if (material < 0 || material >= static_cast<int>(m.materials.size())) return white;
    const int t = m.materials[static_cast<std::size_t>(material)].pbrMetallicRoughness.baseColorTexture.index;
    if (t < 0 || t >= static_cast<int>(m.textures.size())) return white;
    const int src = m.textures[static_cast<std::size_t>(t)].source;
    return src >= 0 && src < static_cast<int>(m.images.size()) ? static_cast<std::uint32_t>(src) : white;
  };

  // 2. Items. With the extension: quad k is the next two triangles of the group of its atlas image
  //    (the writer emits one primitive per atlas image, quads in index order).
  const auto ext_it = m.extensions.find(kImpostorExtension);
  if (ext_it != m.extensions.end()) {
    const tinygltf::Value& ext = ext_it->second;
    const std::vector<float> center = number_array<float>(ext, "center", path), normal = number_array<float>(ext, "normal", path),
                             rect = number_array<float>(ext, "atlasRect", path);
    const auto quads = static_cast<std::size_t>(to_integer<std::uint32_t>(ext.Get("quadCount").GetNumberAsDouble(), path, "quadCount"));
    s.offsets = number_array<std::uint32_t>(ext, "neighborOffsets", path);
    s.neighbors = number_array<std::uint32_t>(ext, "neighbors", path);
    if (center.size() != quads * 3 || normal.size() != quads * 3 || rect.size() != quads * 5 || s.offsets.size() != quads + 1 ||
        s.offsets.back() != s.neighbors.size())
      fail(path, "extension", std::string(kImpostorExtension) + " arrays do not match quadCount " + std::to_string(quads));
    for (std::uint32_t nb : s.neighbors)
      if (nb >= quads) fail(path, "extension", "a neighbour index is out of range");
    std::vector<std::size_t> next(groups.size(), 0);
    for (std::size_t k = 0; k < quads; ++k) {
      const int image = to_integer<int>(rect[k * 5], path, "atlasRect");
      std::size_t g = 0;
      while (g < groups.size() && !(groups[g].material == image && next[g] + 2 <= groups[g].first.size())) ++g;
      if (g == groups.size()) fail(path, "extension", "quad " + std::to_string(k) + " has no triangles in its atlas image's primitive");
      Item it;
      it.first_vertex = groups[g].first[next[g]];
      it.vertex_count = 6;
      if (groups[g].first[next[g] + 1] != it.first_vertex + 3) fail(path, "extension", "quad triangles are not consecutive");
      next[g] += 2;
      it.texture = texture_of(groups[g].material);
      it.center = {center[k * 3], center[k * 3 + 1], center[k * 3 + 2]};
      it.normal = {normal[k * 3], normal[k * 3 + 1], normal[k * 3 + 2]};
      s.items.push_back(it);
    }
    s.has_extension = true;
    s.level = ext.Has("level") ? to_integer<int>(ext.Get("level").GetNumberAsDouble(), path, "level") : -1;
    if (ext.Has("alphaRef")) s.alpha_ref = static_cast<float>(ext.Get("alphaRef").GetNumberAsDouble());
  } else {
    // Plain glTF: consecutive triangle pairs sharing an edge are quads; others stand alone.
    for (const Group& g : groups) {
      for (std::size_t t = 0; t < g.first.size();) {
        const bool pair = t + 1 < g.first.size();
        Item it;
        it.first_vertex = g.first[t];
        it.vertex_count = pair ? 6 : 3;
        it.texture = texture_of(g.material);
        t += pair ? 2 : 1;
        Vec3f sum, area;
        for (std::uint32_t tri = 0; tri < it.vertex_count; tri += 3) {
          Vec3f p[3];
          for (int c = 0; c < 3; ++c) {
            const std::size_t v = (it.first_vertex + tri + static_cast<std::uint32_t>(c)) * 3;
            p[c] = {s.positions[v], s.positions[v + 1], s.positions[v + 2]};
            sum = sum + p[c];
          }
          area = area + cross(p[1] - p[0], p[2] - p[0]);
        }
        it.center = sum * (1.0f / static_cast<float>(it.vertex_count));
        it.normal = normalized(area);
        s.items.push_back(it);
      }
    }
  }
  // 3. One normal per item on all its vertices.
  s.normals.resize(s.positions.size());
  for (const Item& it : s.items)
    for (std::uint32_t v = it.first_vertex; v < it.first_vertex + it.vertex_count; ++v) {
      s.normals[v * 3] = it.normal.x;
      s.normals[v * 3 + 1] = it.normal.y;
      s.normals[v * 3 + 2] = it.normal.z;
    }
  if (s.items.empty()) fail(path, "empty", "the file has no triangles to draw");
  return s;
}

}  // namespace

}  // namespace qf::render
