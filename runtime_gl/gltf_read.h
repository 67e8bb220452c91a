// Reading tinygltf models, shared by the runtime's two loader files (loader.cpp: baked levels,
// point impostors, cluster LODs; engine_loader.cpp: any file as an engine sees it): accessors read
// with bounds checks, extension numbers as integers, images as RGBA. Internal to runtime_gl.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/gltf_component.h"
#include "core/gltf_keys.h"
#include "gltf/compressed_gltf.h"
#include "runtime_gl/engine_scene.h"
#include "runtime_gl/ktx2_image.h"
#include "runtime_gl/webp_image.h"
#include "runtime_gl/scene.h"

namespace qf::render {
namespace gltf {

[[noreturn]] inline void fail(const std::string& path, const std::string& code, const std::string& detail) {
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

  // Floats, or integers as KHR_mesh_quantization allows them (normalized or not), as floats.
  std::vector<float> floats(int index, int components) const {
    const tinygltf::Accessor& a = accessor(index);
    const int size = gltf_component::size_of(a.componentType);
    if (size == 0 || tinygltf::GetNumComponentsInType(a.type) != components)
      fail(path, "accessor", "expected a float or integer accessor with " + std::to_string(components) + " components");
    std::size_t stride = 0;
    const auto n = static_cast<std::size_t>(components), csize = static_cast<std::size_t>(size);
    const unsigned char* p = base(a, csize * n, stride);
    std::vector<float> out(a.count * n);
    for (std::size_t i = 0; i < a.count; ++i)
      for (std::size_t c = 0; c < n; ++c) out[i * n + c] = gltf_component::read(p + i * stride + c * csize, a.componentType, a.normalized);
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

// A KTX2 or WebP image's bytes as the loader kept them (loader.cpp: tinygltf decodes neither), so
// to_image transcodes or decodes them.
constexpr const char* kKtx2Mime = "image/ktx2";
constexpr const char* kWebpMime = "image/webp";

inline Image to_image(const tinygltf::Image& img, const std::string& path) {
  if (img.mimeType == kKtx2Mime && img.width < 0) return decode_ktx2(img.image.data(), img.image.size(), path);
  if (img.mimeType == kWebpMime && img.width < 0) return decode_webp(img.image.data(), img.image.size(), path);
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

// The image a texture shows, as an engine that reads both extensions picks it: its
// KHR_texture_basisu or EXT_texture_webp image, else its source; -1 for none (gltf_input's rule,
// shared with the baker's reader).
inline int texture_source(const tinygltf::Texture& t) { return gltf_input::texture_image(t); }

}  // namespace gltf

// A column-major 4x4 transform, as glTF stores node matrices.
using Mat4d = std::array<double, 16>;

// Per mesh, the world transform of the first node that shows it, depth first from the default
// scene's roots and then from every other root node (MSFT_lod's coarser levels are nodes in no
// scene); the identity for a mesh no node shows. The item views (impostor levels, point impostors,
// cluster LODs) place their vertices by it: a bake has no node transforms, but glTF-Transform's
// quantize and meshopt (KHR_mesh_quantization) move the dequantization into the node.
std::vector<Mat4d> mesh_transforms(const tinygltf::Model& m);
bool is_identity(const Mat4d& w);
// The KHR_texture_transform of material `material`'s base colour texture as u' = k0 u + k1 v + k2,
// v' = k3 u + k4 v + k5 (the identity without one; gltfpack puts its texture-coordinate
// dequantization there); `uv_set` gets its texCoord when it names one. Applied to uv pairs by
// transform_uv_pairs.
std::array<float, 6> base_uv_transform(const tinygltf::Model& m, int material, int& uv_set);
void transform_uv_pairs(const std::array<float, 6>& k, std::vector<float>& uvs);
// xyz triples placed by `w`: points by it, directions by its cofactor matrix, normalized.
void place_points(const Mat4d& w, std::vector<float>& xyz);
void place_directions(const Mat4d& w, std::vector<float>& xyz);

// The root nodes of the default scene (scene 0 when none is named; none when there are no scenes).
std::vector<int> scene_roots(const tinygltf::Model& m);

// The node trees under `roots` as an engine draws them: every mesh primitive placed by its
// composed transform, with its metallic-roughness material. Throws InputError ("render.gltf.*").
EngineScene engine_scene(const tinygltf::Model& m, const std::string& path, const std::vector<int>& roots);

}  // namespace qf::render
