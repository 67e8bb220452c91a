// A mesh input's surface drawn onto a quad (issue 31, after Decoret et al. 2003, "Billboard clouds
// for extreme model simplification"): the triangles a domain stands for, projected orthographically
// along the quad's normal onto its texel grid, supersampled, with the asset's materials and normals.
// Texture resampling (texture.h) calls it for mesh inputs; point sets keep their splat resampling.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace qf {

// The quad's texel grid in its plane: texel (i, j) is centred at centre + s axis_u + t axis_v,
// s = -half_u + (i + 0.5) texel, t = -half_v + (j + 0.5) texel (row j = 0 at t = -half_v).
struct PaintGrid {
  Vec3f center, axis_u, axis_v, normal;
  int width = 0, height = 0;
  double texel = 0, half_u = 0, half_v = 0;
  // Fragments farther than this from the plane (model units) are not the domain's surface: a
  // triangle that reaches the domain with one corner may span the model.
  double slab = 0;
  int samples = 4;  // subsamples per texel side (fewer where the grid is large: at most 4M in all)
  Rgb8 base_color = kUncolouredColor;  // an uncoloured mesh's colour
};

struct PaintedTexel {
  float coverage = 0;                  // share of the texel's subsamples on the surface, 0..1
  std::array<float, 3> color{};        // linear RGB, mean over the covered subsamples
  std::array<float, 3> normal{0, 0, 1};  // mean unit normal there, in (axis_u, axis_v, normal)
  // The material channels (sample/surface_color.h surface_channels), means over the covered
  // subsamples, linear; left at the defaults when the mesh has none (has_material_channels).
  std::array<float, 3> orm{1, 1, 0};     // occlusion, roughness, metallic
  std::array<float, 3> emissive{0, 0, 0};  // RGB
};

// Per texel, row-major: what the mesh shows seen from the quad's front. Each subsample takes the
// fragment of `triangles` nearest the viewer on the normal's side (ties to the lower triangle),
// within the slab, that is not cut out by a MASK material; its colour as an engine shows it
// (sample/surface_color.h: base colour x texture x vertex colour; a mesh without materials its
// vertex colours, else base_color), its material channels (occlusion, roughness, metallic,
// emission, as an engine shows them: surface_channels) and its normal (`normals`, one per vertex, interpolated; the
// face's where empty), turned to the quad's front (a double-sided face is lit so from behind).
std::vector<PaintedTexel> paint_surface(const TriangleMesh& mesh, const std::vector<Vec3f>& normals,
                                        const std::vector<std::uint32_t>& triangles, const PaintGrid& grid);

}  // namespace qf
