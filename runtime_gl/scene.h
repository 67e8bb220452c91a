// What runtime_gl draws, as plain data with no GL in it: a baked impostor level (textured quads
// with their neighbour graph), or a reference (the input point set as splats, or a triangle mesh).
#pragma once

#include <cstdint>
#include <string>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/types.h"

namespace qf::render {

// An 8-bit RGBA image, rows top to bottom, straight (not premultiplied) alpha.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  // Mip levels 1.. of a file that carries its own (KTX2: the baker's coverage-preserving ones);
  // empty: the renderer makes them, as engines do for a PNG.
  std::vector<Image> mips = {};
};

// One drawable of an impostor: `vertex_count` consecutive vertices from `first_vertex`, drawn as
// triangles (a domain primitive's quad is 2 triangles = 6 vertices), with one texture.
struct Item {
  std::uint32_t first_vertex = 0, vertex_count = 0;
  std::uint32_t texture = 0;  // index into ImpostorScene::textures
  Vec3f center, normal;       // sort key and facing test (the extension's, else the triangles')
};

// A loaded .glb. Vertex arrays are flat (x,y,z / u,v per vertex); every vertex of an item carries
// the item's normal (one normal per quad, method.md 7).
struct ImpostorScene {
  std::vector<float> positions, normals, uvs;
  std::vector<Item> items;
  std::vector<Image> textures;
  // The neighbour graph as compressed rows over items: neighbours of item k are
  // neighbors[offsets[k] .. offsets[k+1]). Empty offsets when the file has no extension.
  std::vector<std::uint32_t> offsets, neighbors;
  // Per item, from the extension (empty without it): its basis function's index at the level, and
  // the mean distance of its domain's points to its plane.
  std::vector<std::uint32_t> domains;
  std::vector<float> errors;
  bool has_extension = false;
  int level = -1;               // AMG level, from the extension
  float alpha_ref = 0.1f;       // lock-by-depth alpha test (the extension's alphaRef)
  std::string alpha_mode = "OPAQUE";  // the material's glTF alphaMode (first material)
  float alpha_cutoff = 0.5f;          // the material's alphaCutoff (MASK)
  bool double_sided = false;          // the material's doubleSided: quads seen from behind are drawn too
  Bounds bounds;
};

// A reference point set: oriented splats, one per point (disc of the point's radius, facing its
// normal, in its colour).
struct SplatScene {
  std::vector<Vec3f> positions, normals;
  std::vector<float> radii;
  std::vector<Rgb8> colors;
  Bounds bounds;
};

// A reference triangle mesh with per-vertex normals (area-weighted when the file has none) and
// colours (the constant base colour when it has none).
struct MeshScene {
  std::vector<Vec3f> positions, normals;
  std::vector<Rgb8> colors;
  std::vector<std::uint32_t> indices;
  Bounds bounds;
};

// A point impostor (paper section 5): points in random order, so drawing the first N thins the
// sampling evenly; `pixel` is the LDI pixel side s the points were sampled at.
struct PointImpostorScene {
  std::vector<Vec3f> positions, normals;
  std::vector<Rgb8> colors;  // sRGB, as drawn
  float pixel = 0;
  Bounds bounds;
};

// A vertex-clustering LOD mesh (seed 002): its triangles as a mesh, its thick edges (two vertices
// each, thickness in model units: drawn thickness / R pixels wide, R = the model size of a pixel)
// and its isolated points.
struct ClusterScene {
  MeshScene mesh;
  std::vector<Vec3f> line_positions;  // 2 per edge
  std::vector<Rgb8> line_colors;      // 2 per edge
  std::vector<float> thickness;       // per edge
  std::vector<Vec3f> points;
  std::vector<Rgb8> point_colors;
  float cell = 0;
  Bounds bounds;
};

// How many of a point impostor's n0 points to draw at distance d (paper 5): N = N0 (s Z0 / d)^2
// with Z0 = Camera::focal_pixels(), at most N0 (closer than s Z0 the mesh takes over).
inline std::size_t points_to_draw(std::size_t n0, float pixel, float distance, double z0) {
  const double n = double(n0) * std::pow(pixel * z0 / std::max(double(distance), 1e-30), 2);
  return n >= double(n0) ? n0 : static_cast<std::size_t>(n);
}

// The colour of uncoloured inputs: the same constant the baker gives every output of such inputs,
// so references and baked files match.
constexpr Rgb8 kBaseColor = kUncolouredColor;

}  // namespace qf::render
