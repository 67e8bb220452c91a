// Texture resampling of a domain primitive (paper 3.2; thesis 3.3): the domain's points, projected
// onto its support rectangle, resampled onto a texel grid. RGB = the points' colours, A = the
// basis function Psi of the domain. A mesh input's quads draw the mesh itself instead
// (MeshSurface, surface_paint.h): colour, normals and coverage from its triangles, Psi as the
// seams' alpha.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/sparse.h"
#include "core/types.h"
#include "core/weight_alpha.h"
#include "domains/domains.h"
#include "primitives/support.h"

namespace qf {

enum class ResampleMethod { kLinearAffine, kRadial };
enum class RadialProfile { kConstant, kLinear, kGaussian };
enum class RadialNormalization { kWhenAtLeastOne, kWhenPositive };  // thesis eqs. 3.3 / 3.4

struct TextureOptions {
  float texel_factor = 1.0f;  // texel size = factor x the domain's mean point radius (thesis 5.2.1)
  // ... or this (world units) where larger: the bake sets it per level from the screen size the
  // level is drawn at (BakeOptions::texel_density); 0 = the points' spacing alone.
  double min_texel = 0;
  int max_side = 1024;        // texels; a bigger rectangle gets proportionally larger texels
  ResampleMethod method = ResampleMethod::kLinearAffine;
  RadialProfile profile = RadialProfile::kLinear;  // radial method
  // Linear affine: texels outside the kept triangles but within a point's radius. Constant = each
  // point's splat disc, which is what a point renderer draws (the reference): measured on the
  // octahedron's 8-domain level, linear left the silhouette ~r/2 short and specks where concave
  // triangles were dropped (holes 5.0% of the reference's pixels).
  RadialProfile fallback_profile = RadialProfile::kConstant;
  float width = 1.0f;                              // radial support = width x point radius
  RadialNormalization normalization = RadialNormalization::kWhenAtLeastOne;
  bool extend_colors = true;  // texels with alpha 0 take the colour of the nearest coloured texel
  Rgb8 base_color = kUncolouredColor;  // for inputs without colours
  // Normal maps of curved domains are pulled towards the quad's normal: every texel's normal keeps
  // z >= min(max_min_normal_z, normal_flattening x deviation), deviation = the domain's mean
  // distance to its plane / the rectangle's half-diagonal (flat domains keep their normal maps,
  // and every texel stays in the quad's front hemisphere). A curved domain's texels show surface
  // points away from where its quad draws them, and its quad covers the screen as a plane does:
  // tilted normals there shade the wrong pixels, darker on average than the surface (coarse
  // levels 10-25 grey levels darker than the reference). Measured with the engine method (8
  // views, 256 px) on bunny00, elephant, the dragon and fandisk at ~30/100/300/1000 quads: 8
  // gains +0.2..+2.1 dB at ~30 and up to +1.6 at ~100, and loses at most 0.07 dB at any level
  // (12: +0.4..+2.2 at ~30, but -0.23 at bunny00's 363 quads; 0 = the front hemisphere only).
  double normal_flattening = 8;
  double max_min_normal_z = 0.9;
  // Alpha is stored as 1 - (1 - Psi)^alpha_exponent (core/weight_alpha.h), which a runtime inverts to
  // blend Psi (the extension's alphaExponent). Engines draw the quads with an alpha test
  // (glb.h alpha_cutoff), not the paper's blend: on plain Psi, a cutoff low enough to close the
  // seams between quads (where 3-4 domains share the points, none above 0.5) lies on the outer
  // edge's filtered ramp, outside the surface. With exponent 2 and cutoff 0.3 the seams close at
  // Psi 0.16 (0.2 before) and the outer edges, a step in the texture that filtering ramps, are
  // cut nearer their middle. The bake sets it for mesh inputs
  // (pipeline/bake.h use_surface_edges); 1 stores Psi itself.
  double alpha_exponent = 1;
  // Sub-texel outer edges for an alpha test at this cutoff (0 = off; linear affine only): near the
  // edge of the domain's support (the union of the kept triangles and of discs of edge_radius x
  // the fallback's radius about the points), alpha is capped by cutoff - edge_slope x (signed
  // distance to that edge, in texels), a ramp that bilinear filtering reproduces, so the alpha
  // test cuts on the edge wherever it falls between texel centres; the grid gets one texel more
  // on every side for the ramp's outer end. Without it, an edge steps with the texel grid (at
  // coarse levels a texel spans several point spacings: wavy, and on average half a texel
  // outside the surface) and a quad shows up to its rectangle's rim, where engines clamp to the
  // outer texels. A point's radius is ~0.71 of the spacing of a sampled face, so 0.7 puts the
  // edge half a spacing past the outermost points, where the sampled surface ends; a point set's
  // splats end a whole radius past them (1). The bake sets both (pipeline/bake.h use_surface_edges).
  double edge_cutoff = 0;
  double edge_radius = 0.7;
  double edge_slope = 0.5;
  // Gaps inside the support: the kept triangles leave out those with an edge longer than the sum
  // of its ends' radii, which in the interior of an unevenly sampled face leaves texel-sized
  // holes the ramp would cut (fandisk: dots all over its flat faces, 3% of a level's PNG bytes).
  // A gap the support encloses, no farther than edge_gap x the fallback's mean radius from its
  // edge, joins the support; a larger enclosed one is taken for a hole in the surface.
  double edge_gap = 2.0;
  // A mesh input's quads (MeshSurface): subsamples per texel side of the drawn surface, whose share
  // on the surface is the texel's coverage.
  int coverage_samples = 4;
  // ... and alpha = encoded min(Psi, coverage_gain x coverage): an alpha test shows a texel the
  // surface covers in part or not at all, and a leaf or a beam narrower than a texel covers each
  // of its texels in part (pipeline/bake.h use_surface_edges sets it).
  double coverage_gain = 1;
  // A mesh input's sparse quads (issue 49): where the surface fills less than `sparse_fill` of the
  // texels Psi shows (foliage, lattices, branches: the texels are mostly partly covered), the quad
  // is painted again with texels `sparse_texel_factor` times min_texel. An engine box-filters a
  // PNG's mips: an alpha-tested leaf or beam a texel wide averages with the empty texels about
  // it, drops below the cutoff, and vanishes as soon as the engine samples a finer mip than the
  // base, which a quad seen at an angle does already at its level's size. Texels the size of a
  // pixel at the bottom of the level's band (half its size) keep the engine at the base level
  // through the band. Measured in the bake's comment (pipeline/bake.h use_surface_edges).
  // A closed surface fills its texels (the CGAL meshes: 98-99% of quads at 0.7 or more) and
  // keeps its sharper texels. 0 = off.
  double sparse_fill = 0;
  double sparse_texel_factor = 2;
};

// What a mesh input's quads show (issue 31): the input mesh itself, drawn onto each quad
// (surface_paint.h), instead of colours and normals resampled from its sampled points.
struct MeshSurface {
  const TriangleMesh* mesh = nullptr;
  std::vector<std::uint32_t> point_triangles;  // per point of the bake's set: the triangle it lies on
  // Per mesh vertex, the normals the quads show, as the asset is drawn: its own, else smooth ones
  // where a reader of the format would smooth (OFF, PLY, OBJ: TriangleMesh::smooth_normals);
  // empty: each face's own (a glTF primitive without NORMAL is drawn flat, glTF 2.0 3.7.2.1).
  std::vector<Vec3f> normals;
};

// An RGBA8 image, rows from t = -half_v (row 0) upward; texel (i, j) is centred at
// s = -half_u + (i + 0.5) texel, t = -half_v + (j + 0.5) texel in the rectangle's axes.
struct Texture {
  int width = 0, height = 0;
  float texel = 0;  // world units
  std::vector<std::uint8_t> rgba;  // width * height * 4
  // Tangent-space normal map (glTF convention: RGB = (n.axis_u, n.axis_v, n.normal) * 0.5 + 0.5),
  // width * height * 4 with A = 255; empty when no normals were given.
  std::vector<std::uint8_t> normals;
  // A mesh input's material channels (surface_paint.h), same layout with A = 255, both empty when
  // the mesh has none (TriangleMesh::has_material_channels): `orm` R occlusion, G roughness,
  // B metallic as linear bytes (as glTF's occlusion and metallicRoughness textures read them);
  // `emissive` the emitted colour, sRGB.
  std::vector<std::uint8_t> orm, emissive;
  // Their range over the texels the surface covers, linear: occlusion, roughness, metallic,
  // emissive R, G, B (min > max where none is covered). The level makes a channel that does not
  // vary a factor (atlas.h LevelChannels).
  std::array<float, 6> channel_min{INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
  std::array<float, 6> channel_max{-INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY};
  std::size_t covered = 0;         // texels with alpha > 0
};

// Resamples domain `rect.domain` of Psi onto the rectangle's texel grid. Linear affine (default):
// 2D Delaunay of the projected points (CGAL), triangles with an edge longer than the sum of its
// end points' radii dropped (concavities, thesis fig. 3.8), barycentric interpolation inside;
// texels outside the kept triangles but within a point's radius use the radial profile; all
// others get alpha 0. Radial: sum of the profiles, normalised per texel as the option says.
// With `normals` (one per point, or empty), the same resampling of the point normals gives the
// normal map (paper section 6's first future-work item): per-texel normals, renormalised, in the
// rectangle's tangent frame, so engines light the quad per texel.
// With `surface` (a mesh input), Psi decides only where the quad stands for the surface (the
// seams with its neighbours, its outer reach): the triangles the domain's points lie on are drawn
// onto the quad along its normal (paint_surface), and they give the colour and the normal map,
// and the alpha where they cover less than Psi says: alpha = encoded min(Psi, coverage). So a
// quad shows the asset's own texture, cut-outs and thin parts, not blobs of point splats.
Texture resample_texture(const std::vector<Vec3f>& positions, const std::vector<Rgb8>& colors,
                         const std::vector<Vec3f>& normals, const std::vector<float>& radii, const SparseMatrix& psi,
                         const Domains& domains, const SupportRect& rect, const TextureOptions& options = {},
                         const MeshSurface* surface = nullptr);

}  // namespace qf
