// Plain value types shared by every stage: points, meshes, bounds (architecture.md, "core/types.h").
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace qf {

struct Vec3f {
  float x = 0, y = 0, z = 0;
  float& operator[](int i) { return (&x)[i]; }
  float operator[](int i) const { return (&x)[i]; }
};
inline Vec3f operator+(Vec3f a, Vec3f b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3f operator-(Vec3f a, Vec3f b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3f operator*(Vec3f a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline bool operator==(Vec3f a, Vec3f b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
inline float dot(Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3f cross(Vec3f a, Vec3f b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3f a) { return std::sqrt(dot(a, a)); }
inline bool is_finite(Vec3f a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
// Unit vector in the direction of a; returns `fallback` for a zero (or non-finite) vector.
Vec3f normalized(Vec3f a, Vec3f fallback = {0, 0, 1});
// Like normalized, but returns `a` bit for bit when it is already unit length (to float
// precision), so that reading a file we wrote gives back the same normals.
Vec3f as_unit(Vec3f a, Vec3f fallback = {0, 0, 1});

// The float's shortest decimal form, as a double: JSON writers print it with the digits the float
// needs and no more, so outputs are stable and diffable (gltf-notes.md, determinism). -0 becomes 0.
double canonical_double(float v);

// v rounded to `digits` decimals (report figures such as seconds or megabytes): the division by the
// power of ten makes JSON writers print the short form (0.1, not 0.10000000000000001).
double round_to(double v, int digits);

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
};
inline bool operator==(Rgb8 a, Rgb8 b) { return a.r == b.r && a.g == b.g && a.b == b.b; }
// The colour every output of an uncoloured input carries (impostor textures, mesh LODs, point
// impostors, reference renders), so an engine switching between them shows one look.
constexpr Rgb8 kUncolouredColor{200, 200, 200};

// Axis-aligned box. An empty box has min > max (the default).
struct Bounds {
  Vec3f min{INFINITY, INFINITY, INFINITY};
  Vec3f max{-INFINITY, -INFINITY, -INFINITY};
  bool empty() const { return min.x > max.x; }
  void add(Vec3f p);
  Vec3f size() const { return empty() ? Vec3f{} : max - min; }
  Vec3f center() const { return empty() ? Vec3f{} : (min + max) * 0.5f; }
  float diagonal() const { return length(size()); }
};

// A named per-point scalar (e.g. the classifier); written as an extra float property in PLY.
struct ScalarField {
  std::string name;
  std::vector<float> values;
};

// A point set. positions is always filled; every other per-point array is either empty (absent)
// or has exactly positions.size() entries. Units are those of the input file.
struct PointSet {
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;   // unit length where present
  std::vector<float> radii;     // splat radius, world units, > 0
  std::vector<Rgb8> colors;     // 8-bit sRGB as stored in the file
  std::vector<ScalarField> scalars;
  std::vector<std::string> comments;  // free-text metadata (PLY comments, QSplat comment fragments)

  std::size_t size() const { return positions.size(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_radii() const { return !radii.empty(); }
  bool has_colors() const { return !colors.empty(); }
  Bounds bounds() const;
  std::size_t memory_bytes() const;
};

// The point indices in Morton (Z-order) along 21-bit cells of the bounding box's largest side,
// ties by position, then by index: nearby points get nearby indices, so stages that read a point's
// neighbours touch nearby memory. The same points in any input order give the same sequence, but
// for points at exactly the same position, which keep their input order.
std::vector<std::uint32_t> morton_order(const std::vector<Vec3f>& positions);

// morton_order's parts, for a set sorted in pieces (the out-of-core bake's spill): a point's code
// in the box of the whole set, and the order of two points (code, position, index).
struct MortonKey {
  std::uint64_t code;
  Vec3f position;
  std::uint64_t index;
  bool operator<(const MortonKey& o) const {
    if (code != o.code) return code < o.code;
    if (position.x != o.position.x) return position.x < o.position.x;
    if (position.y != o.position.y) return position.y < o.position.y;
    if (position.z != o.position.z) return position.z < o.position.z;
    return index < o.index;
  }
};
std::uint64_t morton_code(Vec3f p, const Bounds& box);

// The points in `order` (out[i] = points[order[i]]), every per-point array with them.
PointSet permuted(const PointSet& points, const std::vector<std::uint32_t>& order);

// Removes the points i with drop[i] != 0 (drop: one entry per point), in place and in order,
// every per-point array with them (no copy of the set: at 100M points it is 3 GB).
void erase_points(PointSet& points, const std::vector<char>& drop);

using Triangle = std::array<std::uint32_t, 3>;

struct Vec2f {
  float x = 0, y = 0;
};

// An 8-bit RGBA image as stored in the file (colour sRGB, alpha straight), rows top to bottom:
// texture coordinate (0, 0) is the top-left corner of texel (0, 0), as in glTF.
struct TextureImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4
};

// How a texture coordinate outside [0, 1] is brought back (glTF sampler wrapS / wrapT).
enum class TextureWrap : std::uint8_t { kRepeat, kClampToEdge, kMirroredRepeat };
// What a material's alpha means (glTF alphaMode): MASK texels under the cutoff are not surface.
enum class AlphaMode : std::uint8_t { kOpaque, kMask, kBlend };

// A texture a material channel samples: an index into TriangleMesh::textures (-1: none) and its
// sampler's wraps.
struct TextureRef {
  int image = -1;
  TextureWrap wrap_s = TextureWrap::kRepeat, wrap_t = TextureWrap::kRepeat;
};

// A surface's base colour as glTF defines it: base_color (linear RGBA) x the texture's sRGB texels
// x the vertex colour. Texture coordinates come with the triangles (TriangleMesh::corner_uvs), with
// any texture transform already applied.
struct SurfaceMaterial {
  std::string name;
  std::array<float, 4> base_color{1, 1, 1, 1};
  int texture = -1;  // index into TriangleMesh::textures, or -1
  TextureWrap wrap_s = TextureWrap::kRepeat, wrap_t = TextureWrap::kRepeat;
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;  // what engines cull (sampling sees both sides either way)
  // The other channels of glTF's metallic-roughness model (glTF 2.0 3.9.2, 3.9.3). Defaults are a
  // rough dielectric without emission: what formats without these channels (OFF, PLY, OBJ+MTL) are
  // drawn as; a glTF file's materials carry their own factors (glTF's default: metallic 1).
  // Textures sample the same texture coordinates as the base colour (corner_uvs).
  float metallic = 0, roughness = 1;        // factors, 0..1
  TextureRef metallic_roughness;            // linear texels: G roughness, B metallic (x the factors)
  std::array<float, 3> emissive{0, 0, 0};  // linear RGB factor
  TextureRef emissive_texture;              // sRGB texels (x the factor)
  TextureRef occlusion;                     // linear texels, R: occlusion = 1 + strength (R - 1)
  float occlusion_strength = 1;
};

// An indexed triangle mesh; per-vertex normals/colours are empty or one per position. Materials are
// optional: triangle_materials is empty (no material: the default look) or one index into materials
// per triangle; corner_uvs is empty or one triple per triangle (per corner, since texture seams
// split what positions share).
struct TriangleMesh {
  std::vector<Vec3f> positions;
  std::vector<Triangle> triangles;
  std::vector<Vec3f> normals;
  std::vector<Rgb8> colors;
  std::vector<std::string> comments;
  std::vector<SurfaceMaterial> materials;
  std::vector<std::uint32_t> triangle_materials;
  std::vector<std::array<Vec2f, 3>> corner_uvs;
  std::vector<TextureImage> textures;

  // True when the surface has a colour of its own: vertex colours, or a material with a texture or
  // a base colour other than white.
  bool has_surface_color() const;
  // True when a material has a metallic, roughness, occlusion or emissive channel other than the
  // defaults' rough dielectric without emission (a factor or a texture).
  bool has_material_channels() const;

  // Smooth vertex normals: area-weighted face normals summed over the vertices at one position
  // (copies of a vertex split at a texture seam get the same normal); (0, 0, 1) where they cancel.
  std::vector<Vec3f> smooth_normals() const;

  Bounds bounds() const;
  std::size_t memory_bytes() const;
};

}  // namespace qf
