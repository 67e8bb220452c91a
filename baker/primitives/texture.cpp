// Texture resampling: linear affine (CGAL 2D Delaunay, concavity edges dropped, radial fallback)
// or radial basis functions; colour extension into empty texels (thesis 3.3).
#include "primitives/texture.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>

#include "core/color.h"
#include "primitives/surface_paint.h"

namespace qf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// A vertex carries its sample's index and radius: the faces loop reads only the vertices (the
// concavity test, the texel bounds) and reaches into the samples for texels inside a triangle.
// With the samples read for every face, 1M points spent ~2 s per level in cache misses there.
struct VertexInfo {
  std::uint32_t sample;
  double r;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;

// Per-point channels resampled together: colour (3), tangent-space normal (3).
constexpr int kChannels = 6;

struct Sample {
  double s, t;  // rectangle coordinates
  double r;     // splat radius
  double value[kChannels];
  double alpha;  // Psi of the domain
  double join;   // a Delaunay edge longer than the sum of its ends' `join` is a concavity: r, or more when merged
};

// Accumulates weighted channels and alpha per texel. Channels are weighted by each point's Psi
// too (`value_weight`): a texel shows the colour and normal of the part of the surface this quad
// stands for, not of the neighbouring domain's points that reach into its rectangle with a small
// Psi (at a crease they are the other face: measured on the octahedron, an unweighted mean put a
// band of the next face's colour, lit as this face, along every crease).
struct Accumulator {
  std::vector<double> value, value_weight, alpha, weight;
  std::vector<char> done;  // texel set by the linear affine interpolation
  explicit Accumulator(std::size_t n)
      : value(kChannels * n, 0.0), value_weight(n, 0.0), alpha(n, 0.0), weight(n, 0.0), done(n, 0) {}
};

double profile(RadialProfile p, double d, double support) {
  if (d > support) return 0.0;
  switch (p) {
    case RadialProfile::kConstant: return 1.0;
    case RadialProfile::kLinear: return (support - d) / support;
    case RadialProfile::kGaussian: {
      const double sigma = support / 3.0;
      return std::exp(-d * d / (2 * sigma * sigma));
    }
  }
  return 0.0;
}

// |(x, y)| without std::hypot's care for overflow (texel distances are far from it; hypot was
// the edge ramp's largest cost).
double length(double x, double y) { return std::sqrt(x * x + y * y); }

// The texel grid in rectangle coordinates (centred on the rectangle: texel centres run from
// -half to +half), and walks over the texels whose centres lie in a box or near a point.
struct Grid {
  int width, height;
  double texel, half_u, half_v;
  double s(int i) const { return -half_u + (i + 0.5) * texel; }
  double t(int j) const { return -half_v + (j + 0.5) * texel; }
  // f(k, s, t) for every texel centre (s, t) in [s0, s1] x [t0, t1]; k = the texel's index.
  template <class F>
  void box(double s0, double s1, double t0, double t1, F&& f) const {
    const int i0 = std::max(0, static_cast<int>(std::ceil((s0 + half_u) / texel - 0.5)));
    const int i1 = std::min(width - 1, static_cast<int>(std::floor((s1 + half_u) / texel - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((t0 + half_v) / texel - 0.5)));
    const int j1 = std::min(height - 1, static_cast<int>(std::floor((t1 + half_v) / texel - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) f(static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i), s(i), t(j));
  }
  template <class F>
  void around(double ps, double pt, double reach, F&& f) const {
    box(ps - reach, ps + reach, pt - reach, pt + reach, f);
  }
};

// Adds every sample's radial profile to the texels it reaches (skipping texels already done).
void splat_radial(const std::vector<Sample>& samples, const Grid& g, const TextureOptions& o, Accumulator& acc) {
  const RadialProfile shape = o.method == ResampleMethod::kLinearAffine ? o.fallback_profile : o.profile;
  for (const Sample& p : samples) {
    const double support = o.width * p.r;
    g.around(p.s, p.t, support, [&](std::size_t k, double s, double t) {
      if (acc.done[k]) return;
      const double w = profile(shape, std::hypot(s - p.s, t - p.t), support);
      if (w <= 0) return;
      for (int c = 0; c < kChannels; ++c) acc.value[kChannels * k + static_cast<std::size_t>(c)] += w * p.alpha * p.value[c];
      acc.value_weight[k] += w * p.alpha;
      acc.alpha[k] += w * p.alpha;
      acc.weight[k] += w;
    });
  }
}

// An edge of the kept triangles' outline (a kept triangle on one side only), with its end points'
// Psi.
struct Segment {
  double s0, t0, s1, t1, psi0, psi1;
};

// The kept triangles' outline and the samples on it (an end of an outline edge, or a corner of
// no kept triangle): only their discs can reach past the triangles.
struct Outline {
  std::vector<Segment> segments;
  std::vector<char> on_edge;  // per sample
};

// Linear affine interpolation over the Delaunay triangles whose edges are all no longer than the
// sum of their end points' radii. With `outline`, the kept triangles' outline goes there.
void interpolate_triangles(const std::vector<Sample>& samples, const Grid& g, Accumulator& acc, Outline* outline) {
  std::vector<std::pair<Kernel::Point_2, VertexInfo>> pts;
  pts.reserve(samples.size());
  for (std::uint32_t k = 0; k < samples.size(); ++k) pts.push_back({Kernel::Point_2(samples[k].s, samples[k].t), {k, samples[k].join}});
  Delaunay dt;
  dt.insert(pts.begin(), pts.end());
  if (outline) outline->on_edge.assign(samples.size(), 1);
  if (dt.dimension() < 2) return;
  struct Corner {
    double s, t, r;
  };
  const auto corners = [](Delaunay::Face_handle f, Corner* v) {
    for (int c = 0; c < 3; ++c) {
      const auto vh = f->vertex(c);
      v[c] = {vh->point().x(), vh->point().y(), vh->info().r};
    }
  };
  const auto kept = [&](Delaunay::Face_handle f) {
    if (dt.is_infinite(f)) return false;
    Corner v[3];
    corners(f, v);
    for (int c = 0; c < 3; ++c) {
      const Corner &a = v[c], &b = v[(c + 1) % 3];
      const double ds = a.s - b.s, dt2 = a.t - b.t;
      if (ds * ds + dt2 * dt2 > (a.r + b.r) * (a.r + b.r)) return false;  // concave
    }
    return (v[1].s - v[0].s) * (v[2].t - v[0].t) - (v[2].s - v[0].s) * (v[1].t - v[0].t) != 0;
  };
  std::vector<char> on_outline;  // per sample: an end of an outline edge
  if (outline) on_outline.assign(samples.size(), 0);
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    if (!kept(f)) continue;
    Corner v[3];
    corners(f, v);
    if (outline)
      for (int c = 0; c < 3; ++c) {
        outline->on_edge[f->vertex(c)->info().sample] = 0;  // a corner of a kept triangle
        if (kept(f->neighbor(c))) continue;
        const std::uint32_t ia = f->vertex(f->cw(c))->info().sample, ib = f->vertex(f->ccw(c))->info().sample;
        outline->segments.push_back({samples[ia].s, samples[ia].t, samples[ib].s, samples[ib].t, samples[ia].alpha, samples[ib].alpha});
        on_outline[ia] = on_outline[ib] = 1;
      }
    const double det = (v[1].s - v[0].s) * (v[2].t - v[0].t) - (v[2].s - v[0].s) * (v[1].t - v[0].t);
    g.box(std::min({v[0].s, v[1].s, v[2].s}), std::max({v[0].s, v[1].s, v[2].s}), std::min({v[0].t, v[1].t, v[2].t}),
          std::max({v[0].t, v[1].t, v[2].t}), [&](std::size_t k, double s, double t) {
            const double b1 = ((s - v[0].s) * (v[2].t - v[0].t) - (v[2].s - v[0].s) * (t - v[0].t)) / det;
            const double b2 = ((v[1].s - v[0].s) * (t - v[0].t) - (s - v[0].s) * (v[1].t - v[0].t)) / det;
            const double b0 = 1 - b1 - b2;
            constexpr double kEdge = -1e-9;  // texels on a shared edge belong to the first triangle that sees them
            if (b0 < kEdge || b1 < kEdge || b2 < kEdge) return;
            if (acc.done[k]) return;
            acc.done[k] = 1;
            const double b[3] = {b0, b1, b2};
            for (int c = 0; c < 3; ++c) {
              const Sample& p = samples[f->vertex(c)->info().sample];
              for (int ch = 0; ch < kChannels; ++ch) acc.value[kChannels * k + static_cast<std::size_t>(ch)] += b[c] * p.alpha * p.value[ch];
              acc.value_weight[k] += b[c] * p.alpha;
              acc.alpha[k] += b[c] * p.alpha;
            }
            acc.weight[k] = 1.0;
          });
  }
  if (outline)
    for (std::size_t i = 0; i < samples.size(); ++i) outline->on_edge[i] |= on_outline[i];
}

std::uint8_t to8(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0))); }

// Texels with alpha 0 take the colour (and normal and material channels) of the nearest texel with alpha > 0 (breadth
// first over the grid, 4-neighbourhood, sources in index order), so filtering never pulls in black
// (thesis 3.3.4).
void extend_colors(Texture& tex) {
  const std::size_t n = static_cast<std::size_t>(tex.width) * static_cast<std::size_t>(tex.height);
  std::vector<char> has(n, 0);
  std::deque<std::size_t> queue;
  for (std::size_t k = 0; k < n; ++k)
    if (tex.rgba[4 * k + 3] > 0) has[k] = 1, queue.push_back(k);
  if (queue.empty()) return;
  while (!queue.empty()) {
    const std::size_t k = queue.front();
    queue.pop_front();
    const int i = static_cast<int>(k % static_cast<std::size_t>(tex.width)), j = static_cast<int>(k / static_cast<std::size_t>(tex.width));
    const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
    for (int e = 0; e < 4; ++e) {
      const int a = i + di[e], b = j + dj[e];
      if (a < 0 || b < 0 || a >= tex.width || b >= tex.height) continue;
      const std::size_t q = static_cast<std::size_t>(b) * static_cast<std::size_t>(tex.width) + static_cast<std::size_t>(a);
      if (has[q]) continue;
      has[q] = 1;
      for (int c = 0; c < 3; ++c) tex.rgba[4 * q + static_cast<std::size_t>(c)] = tex.rgba[4 * k + static_cast<std::size_t>(c)];
      for (std::vector<std::uint8_t>* image : {&tex.normals, &tex.orm, &tex.emissive})
        if (!image->empty())
          for (int c = 0; c < 3; ++c) (*image)[4 * q + static_cast<std::size_t>(c)] = (*image)[4 * k + static_cast<std::size_t>(c)];
      queue.push_back(q);
    }
  }
}

// The distance from (s, t) to the segment a-b, and (in `u`) the nearest point's parameter.
double distance_to_segment(double s, double t, double as, double at, double bs, double bt, double* u = nullptr) {
  const double es = bs - as, et = bt - at, len2 = es * es + et * et;
  const double x = len2 > 0 ? std::clamp(((s - as) * es + (t - at) * et) / len2, 0.0, 1.0) : 0.0;
  if (u) *u = x;
  return length(s - as - x * es, t - at - x * et);
}

// A texel's distance to the support (negative inside a disc) and the support's nearest point, with
// its Psi.
struct Nearest {
  double d = std::numeric_limits<double>::infinity(), s = 0, t = 0, psi = 0;
};

// Marks as kGap in `support` every component of non-support texels (4-neighbourhood) that touches
// no texel of the grid's rim and whose distances to the support (`d`) are all within `reach`.
constexpr char kGap = 2;
void fill_gaps(const std::vector<Nearest>& near, const Grid& g, double reach, std::vector<char>& support) {
  const std::size_t w = static_cast<std::size_t>(g.width), h = static_cast<std::size_t>(g.height), n = support.size();
  std::vector<char> seen(n, 0);
  std::vector<std::size_t> component;
  for (std::size_t first = 0; first < n; ++first) {
    if (support[first] || seen[first]) continue;
    component.assign(1, first);
    seen[first] = 1;
    bool enclosed = true;
    double farthest = 0;
    for (std::size_t c = 0; c < component.size(); ++c) {
      const std::size_t k = component[c], i = k % w, j = k / w;
      enclosed = enclosed && i > 0 && j > 0 && i + 1 < w && j + 1 < h;
      farthest = std::max(farthest, near[k].d);
      const auto visit = [&](std::size_t q) {
        if (!support[q] && !seen[q]) seen[q] = 1, component.push_back(q);
      };
      if (i > 0) visit(k - 1);
      if (i + 1 < w) visit(k + 1);
      if (j > 0) visit(k - w);
      if (j + 1 < h) visit(k + w);
    }
    if (enclosed && farthest <= reach)
      for (const std::size_t k : component) support[k] = kGap;
  }
}

// Sub-texel outer edges (TextureOptions::edge_cutoff). The support is the union of the kept
// triangles (`inside` texels) and of discs of radius edge_radius x width x r about the points
// (those on the outline: the others' lie in their triangles but for slivers).
// Alpha is capped by cutoff + slope x (signed distance to the support's edge, in texels): a ramp
// that bilinear filtering reproduces, so the alpha test cuts on the edge wherever it falls between
// texel centres. Texels outside get their alpha from the ramp alone, at most the (encoded) Psi at
// their nearest support point; their colours are those extend_colors gave them.
void ramp_edges(const std::vector<Sample>& samples, const Outline& outline, const std::vector<char>& inside,
                const Grid& g, double mean_radius, const TextureOptions& o, Texture& tex) {
  const double cutoff = o.edge_cutoff, slope = o.edge_slope / g.texel;  // alpha per unit distance
  const double reach_out = std::max(cutoff / slope, g.texel);           // the outside ramp's width
  const double reach_in = (1 - cutoff) / slope;                         // the inside ramp's width
  const std::size_t n = inside.size();
  constexpr double kFar = std::numeric_limits<double>::infinity();
  // 1. Outside texels: the distance to the support and its nearest point there (with its Psi).
  std::vector<Nearest> near(n);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!outline.on_edge[i]) continue;
    const Sample& p = samples[i];
    const double rho = o.edge_radius * o.width * p.r;
    g.around(p.s, p.t, rho + reach_out, [&](std::size_t k, double s, double t) {
      const double len = length(s - p.s, t - p.t), d = len - rho;
      if (d >= near[k].d) return;
      const double f = len > 0 ? rho / len : 0.0;
      near[k] = {d, p.s + f * (s - p.s), p.t + f * (t - p.t), p.alpha};
    });
  }
  for (const Segment& e : outline.segments) {
    const double es = e.s1 - e.s0, et = e.t1 - e.t0;
    g.around(0.5 * (e.s0 + e.s1), 0.5 * (e.t0 + e.t1), 0.5 * length(es, et) + reach_out, [&](std::size_t k, double s, double t) {
      double u = 0;
      const double d = distance_to_segment(s, t, e.s0, e.t0, e.s1, e.t1, &u);
      if (d < near[k].d) near[k] = {d, e.s0 + u * es, e.t0 + u * et, e.psi0 + u * (e.psi1 - e.psi0)};
    });
  }
  // 2. Gaps (TextureOptions::edge_gap): a component of texels outside the support that does not
  //    reach the grid's rim and lies within edge_gap x the mean radius of its edge joins it, with
  //    the Psi of its edge where the splats left it none.
  std::vector<char> support(n);
  for (std::size_t k = 0; k < n; ++k) support[k] = inside[k] || near[k].d < 0;
  fill_gaps(near, g, o.edge_gap * o.width * mean_radius, support);
  for (std::size_t k = 0; k < n; ++k)
    if (support[k] == kGap && tex.rgba[4 * k + 3] == 0) tex.rgba[4 * k + 3] = to8(255.0 * encode_alpha(near[k].psi, o.alpha_exponent));
  const auto in_support = [&](std::size_t k) { return support[k] != 0; };
  const auto rim = [&](std::size_t k) { return !in_support(k) && near[k].d < reach_out; };
  // 3. Inside texels: the distance to the edge, approximated by the polyline through the nearest
  //    support points of the outside texels next to it (chords between 4-neighbours, each point
  //    itself where it has none). The points lie on the edge about a texel apart, so the polyline
  //    follows it to a chord's sagitta; a tangent line per point does not: on a union of discs
  //    the local normal swings by +-45 degrees between points, and lines a texel long cut deep
  //    into the inside. A spike narrower than a texel falls between the points: there the bound
  //    |x - y| - d(x) over the outside texels x holds the distance (the segment from y to x
  //    leaves the support at least the distance from y, and then runs at least d(x)).
  std::vector<double> depth(n, kFar);
  const auto chord = [&](const Nearest& a, const Nearest& b) {
    const double cs = 0.5 * (a.s + b.s), ct = 0.5 * (a.t + b.t);
    g.around(cs, ct, 0.5 * length(b.s - a.s, b.t - a.t) + reach_in, [&](std::size_t q, double s, double t) {
      if (in_support(q)) depth[q] = std::min(depth[q], distance_to_segment(s, t, a.s, a.t, b.s, b.t));
    });
  };
  const std::size_t w = static_cast<std::size_t>(g.width);
  for (std::size_t k = 0; k < n; ++k) {
    if (!rim(k)) continue;
    const double xs = g.s(static_cast<int>(k % w)), xt = g.t(static_cast<int>(k / w)), dk = near[k].d;
    g.around(xs, xt, reach_in + dk, [&](std::size_t q, double s, double t) {
      if (in_support(q)) depth[q] = std::min(depth[q], length(s - xs, t - xt) - dk);
    });
    const bool right = k % w + 1 < w && rim(k + 1), up = k + w < n && rim(k + w);
    if (right) chord(near[k], near[k + 1]);
    if (up) chord(near[k], near[k + w]);
    if (!right && !up) chord(near[k], near[k]);
  }
  // 4. The ramp.
  tex.covered = 0;
  for (std::size_t k = 0; k < n; ++k) {
    std::uint8_t& a = tex.rgba[4 * k + 3];
    if (in_support(k)) {
      if (depth[k] < kFar) a = std::min(a, to8(255.0 * (cutoff + slope * depth[k])));
    } else if (near[k].d < kFar) {
      a = std::min(to8(255.0 * encode_alpha(near[k].psi, o.alpha_exponent)), to8(255.0 * (cutoff - slope * near[k].d)));
    } else {
      a = 0;
    }
    tex.covered += a > 0;
  }
}

// The unit normal of an accumulated normal `v` (tangent space), tilted towards the quad's normal
// until its z is at least `min_z`, its direction about z kept (TextureOptions::normal_flattening).
std::array<double, 3> within_cone(const double* v, double min_z) {
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(len > 0)) return {0, 0, 1};
  const std::array<double, 3> n{v[0] / len, v[1] / len, v[2] / len};
  if (n[2] >= min_z) return n;
  const double xy = std::hypot(n[0], n[1]);
  if (!(xy > 0)) return {0, 0, 1};
  const double s = std::sqrt(1 - min_z * min_z) / xy;
  return {n[0] * s, n[1] * s, min_z};
}

// The domain's triangles (surface.point_triangles of its points), ascending, without repeats.
std::vector<std::uint32_t> domain_triangles(const MeshSurface& surface, const Domains& domains, std::size_t d) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t q = domains.offsets[d]; q < domains.offsets[d + 1]; ++q) out.push_back(surface.point_triangles[domains.points[q]]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Texel k's material channels from what the mesh shows there, and their ranges.
void paint_channels(const PaintedTexel& p, std::size_t k, Texture& tex) {
  for (std::size_t c = 0; c < 3; ++c) {
    tex.orm[4 * k + c] = to8(255.0 * p.orm[c]);
    tex.emissive[4 * k + c] = linear_to_srgb8(p.emissive[c]);
    const float v[2] = {p.orm[c], p.emissive[c]};
    for (std::size_t j = 0; j < 2; ++j) {
      tex.channel_min[3 * j + c] = std::min(tex.channel_min[3 * j + c], v[j]);
      tex.channel_max[3 * j + c] = std::max(tex.channel_max[3 * j + c], v[j]);
    }
  }
}

// Colour, normals (and material channels) of the texels the mesh covers, from the mesh drawn onto the quad; returns
// each texel's coverage.
std::vector<double> paint_from_mesh(const MeshSurface& surface, const std::vector<std::uint32_t>& triangles, const SupportRect& r,
                                    const Grid& grid, double slab, double min_z, const TextureOptions& o, Texture& tex) {
  PaintGrid pg{r.center, r.axis_u, r.axis_v, r.normal, grid.width, grid.height, grid.texel, grid.half_u, grid.half_v,
               slab, o.coverage_samples, o.base_color};
  const std::vector<PaintedTexel> painted = paint_surface(*surface.mesh, surface.normals, triangles, pg);
  std::vector<double> coverage(painted.size(), 0.0);
  if (surface.mesh->has_material_channels()) {
    tex.orm.assign(4 * painted.size(), 255);
    tex.emissive.assign(4 * painted.size(), 255);
    for (std::size_t k = 0; k < painted.size(); ++k) tex.orm[4 * k + 2] = 0, std::fill_n(&tex.emissive[4 * k], 3, 0);
  }
  for (std::size_t k = 0; k < painted.size(); ++k) {
    const PaintedTexel& p = painted[k];
    coverage[k] = p.coverage;
    if (!(p.coverage > 0)) continue;
    for (int c = 0; c < 3; ++c) tex.rgba[4 * k + static_cast<std::size_t>(c)] = linear_to_srgb8(p.color[static_cast<std::size_t>(c)]);
    if (!tex.orm.empty()) paint_channels(p, k, tex);
    if (!tex.normals.empty()) {
      const double v[3] = {p.normal[0], p.normal[1], p.normal[2]};
      const std::array<double, 3> nm = within_cone(v, min_z);
      for (int c = 0; c < 3; ++c) tex.normals[4 * k + static_cast<std::size_t>(c)] = to8(127.5 * (nm[static_cast<std::size_t>(c)] + 1.0));
    }
  }
  return coverage;
}

// Alpha no higher than the coverage says (TextureOptions::coverage_gain, encoded as Psi is);
// `covered` recounted. Returns the quad's fill: the mean coverage of the texels Psi shows (alpha at
// or above the cutoff before the cap), 1 where it shows none.
double cap_by_coverage(const std::vector<double>& coverage, const TextureOptions& o, Texture& tex) {
  tex.covered = 0;
  const std::uint8_t cutoff = std::max<std::uint8_t>(1, to8(255.0 * o.edge_cutoff));
  double covered = 0, shown = 0;
  for (std::size_t k = 0; k < coverage.size(); ++k) {
    std::uint8_t& a = tex.rgba[4 * k + 3];
    if (a >= cutoff) covered += std::min(1.0, coverage[k]), shown += 1;
    a = std::min(a, to8(255.0 * encode_alpha(std::min(1.0, o.coverage_gain * coverage[k]), o.alpha_exponent)));
    tex.covered += a > 0;
  }
  return shown > 0 ? covered / shown : 1.0;
}

// A domain with many points a texel is merged per cell of 1/kMergeCells of a texel before the
// resampling: a coarse level of a dense set gathers millions of points a quad for a few hundred
// texels (the 22-quad level of a 100M-point torus: up to 8M points a quad), and the Delaunay of
// every point cost ~300 bytes and ~1 us a point, for texels that sample the surface at their
// centres, which the cells' means give as well (a box filter a third of a texel wide). Merging
// starts where the points outnumber the cells kMergeAbove times, so the cells never hold more
// memory than the points' samples would; below it the samples are the points, unchanged.
constexpr int kMergeCells = 3;
constexpr double kMergeAbove = 2.0;

// Sums of the points in one cell.
struct CellSum {
  double s = 0, t = 0, r = 0, alpha = 0;
  double value[kChannels] = {}, plain[kChannels] = {};
  std::uint32_t count = 0;
};

// The domain's samples: each point in rectangle coordinates with its colour, its normal in the
// rectangle's frame and its Psi, or the cells' means (values weighted by Psi as the texels' are;
// the Delaunay joins a merged sample to its neighbours over half a texel at least, as adjacent
// cells' means may lie up to 2.9 cells apart). `slab` gets the points' farthest distance from the
// plane.
std::vector<Sample> domain_samples(const std::vector<Vec3f>& positions, const std::vector<Rgb8>& colors,
                                   const std::vector<Vec3f>& normals, const std::vector<float>& radii, const SparseMatrix& psi,
                                   const Domains& domains, const SupportRect& rect, const SupportRect& grid_rect, const Texture& tex,
                                   const TextureOptions& o, double& slab) {
  const std::size_t d = rect.domain;
  const auto sample_of = [&](std::uint32_t i) {
    const Vec3f x = positions[i] - rect.center;
    slab = std::max(slab, std::fabs(double(dot(x, rect.normal))));
    Sample sm{dot(x, rect.axis_u), dot(x, rect.axis_v), radii[i], {0, 0, 0, 0, 0, 1}, psi.coeff(i, static_cast<Eigen::Index>(d)), radii[i]};
    const Rgb8 c = colors.empty() ? o.base_color : colors[i];
    sm.value[0] = c.r, sm.value[1] = c.g, sm.value[2] = c.b;
    if (!normals.empty()) {
      const Vec3f n = normals[i];
      sm.value[3] = dot(n, rect.axis_u), sm.value[4] = dot(n, rect.axis_v), sm.value[5] = dot(n, rect.normal);
    }
    return sm;
  };
  const std::size_t points = domains.offsets[d + 1] - domains.offsets[d];
  const std::size_t cw = static_cast<std::size_t>(tex.width) * kMergeCells, ch = static_cast<std::size_t>(tex.height) * kMergeCells;
  std::vector<Sample> samples;
  if (double(points) <= kMergeAbove * double(cw * ch)) {
    samples.reserve(points);
    for (std::uint32_t q = domains.offsets[d]; q < domains.offsets[d + 1]; ++q) samples.push_back(sample_of(domains.points[q]));
    return samples;
  }
  const double cell = double(tex.texel) / kMergeCells;
  std::vector<CellSum> cells(cw * ch);
  for (std::uint32_t q = domains.offsets[d]; q < domains.offsets[d + 1]; ++q) {
    const Sample p = sample_of(domains.points[q]);
    const auto at = [&](double v, double half, std::size_t size) {
      return std::min(size - 1, static_cast<std::size_t>(std::max(0.0, std::floor((v + half) / cell))));
    };
    CellSum& c = cells[at(p.t, grid_rect.half_v, ch) * cw + at(p.s, grid_rect.half_u, cw)];
    c.s += p.s, c.t += p.t, c.r += p.r, c.alpha += p.alpha, ++c.count;
    for (int k = 0; k < kChannels; ++k) c.value[k] += p.alpha * p.value[k], c.plain[k] += p.value[k];
  }
  for (const CellSum& c : cells) {
    if (c.count == 0) continue;
    const double inv = 1.0 / c.count;
    Sample m{c.s * inv, c.t * inv, c.r * inv, {}, c.alpha * inv, std::max(c.r * inv, 1.5 * cell)};
    for (int k = 0; k < kChannels; ++k) m.value[k] = c.alpha > 0 ? c.value[k] / c.alpha : c.plain[k] * inv;
    samples.push_back(m);
  }
  return samples;
}

// resample_texture at the texel size `o` gives; `fill` gets the quad's fill (cap_by_coverage), 1
// for a point set.
Texture resample_at(const std::vector<Vec3f>& positions, const std::vector<Rgb8>& colors, const std::vector<Vec3f>& normals,
                    const std::vector<float>& radii, const SparseMatrix& psi, const Domains& domains, const SupportRect& rect,
                    const TextureOptions& o, const MeshSurface* surface, double& fill) {
  Texture tex;
  fill = 1;
  // 1. The texel grid: texel = factor x mean radius (or min_texel where larger), at most max_side
  //    texels a side. With sub-texel edges, one texel more on every side: the support's edge may
  //    lie anywhere in the rectangle's outer texel, and its ramp needs a texel centre beyond it (an
  //    engine clamps to the outer texels: without one the quad would show up to its rim).
  const bool ramp = o.edge_cutoff > 0 && o.method == ResampleMethod::kLinearAffine;
  const int pad = ramp ? 2 : 0;
  double texel = std::max({1e-30, double(o.texel_factor) * rect.mean_radius, o.min_texel});
  const double longest = 2.0 * std::max(rect.half_u, rect.half_v);
  const int max_side = std::max(1, o.max_side - pad);
  if (longest / texel > max_side) texel = longest / max_side;
  tex.texel = static_cast<float>(texel);
  tex.width = std::max(1, static_cast<int>(std::ceil(2.0 * rect.half_u / texel))) + pad;
  tex.height = std::max(1, static_cast<int>(std::ceil(2.0 * rect.half_v / texel))) + pad;
  // The grid is centred on the rectangle: texel centres run from -half to +half.
  SupportRect r = rect;
  r.half_u = static_cast<float>(0.5 * tex.width * texel);
  r.half_v = static_cast<float>(0.5 * tex.height * texel);
  // 2. The domain's points in rectangle coordinates, merged per cell where there are many a texel.
  const std::size_t d = rect.domain;
  double slab = 0;  // the points' farthest distance from the plane
  const std::vector<Sample> samples = domain_samples(positions, colors, normals, radii, psi, domains, rect, r, tex, o, slab);
  // 3. Resample.
  const std::size_t n = static_cast<std::size_t>(tex.width) * static_cast<std::size_t>(tex.height);
  Accumulator acc(n);
  const Grid grid{tex.width, tex.height, tex.texel, r.half_u, r.half_v};
  Outline outline;
  if (o.method == ResampleMethod::kLinearAffine) interpolate_triangles(samples, grid, acc, ramp ? &outline : nullptr);
  splat_radial(samples, grid, o, acc);
  tex.rgba.assign(4 * n, 0);
  const double deviation = rect.error / std::max(1e-30, std::hypot(double(rect.half_u), double(rect.half_v)));
  const double min_z = std::clamp(o.normal_flattening * deviation, 0.0, o.max_min_normal_z);
  if (!normals.empty()) {
    tex.normals.assign(4 * n, 255);
    for (std::size_t k = 0; k < n; ++k) tex.normals[4 * k] = tex.normals[4 * k + 1] = 128;  // (0, 0, 1)
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double w = acc.weight[k], vw = acc.value_weight[k];
    if (!(w > 0) || !(vw > 0)) continue;  // no Psi here: alpha 0, the colour comes from extend_colors
    if (!normals.empty()) {
      const std::array<double, 3> nm = within_cone(&acc.value[kChannels * k + 3], min_z);
      for (int c = 0; c < 3; ++c) tex.normals[4 * k + static_cast<std::size_t>(c)] = to8(127.5 * (nm[static_cast<std::size_t>(c)] + 1.0));
    }
    // Colours are always a weighted mean; alpha is normalised only as the criterion says (an
    // interpolated texel has weight 1 already).
    const bool normalize = o.normalization == RadialNormalization::kWhenPositive ? w > 0 : w >= 1.0;
    const double alpha = normalize ? acc.alpha[k] / w : acc.alpha[k];
    for (int c = 0; c < 3; ++c) tex.rgba[4 * k + static_cast<std::size_t>(c)] = to8(acc.value[kChannels * k + static_cast<std::size_t>(c)] / vw);
    tex.rgba[4 * k + 3] = to8(255.0 * encode_alpha(alpha, o.alpha_exponent));
    tex.covered += tex.rgba[4 * k + 3] > 0;
  }
  // 4. A mesh input: its surface drawn onto the quad (colour, normals, coverage), within the slab of
  //    the domain's points and a spacing more.
  std::vector<double> coverage;
  if (surface && surface->mesh) {
    coverage = paint_from_mesh(*surface, domain_triangles(*surface, domains, d), r, grid, slab + 2.0 * rect.mean_radius, min_z, o, tex);
    (void)cap_by_coverage(coverage, o, tex);
  }
  if (o.extend_colors) extend_colors(tex);
  if (ramp) ramp_edges(samples, outline, acc.done, grid, rect.mean_radius, o, tex);
  if (!coverage.empty()) fill = cap_by_coverage(coverage, o, tex);  // the ramp's outside texels too
  return tex;
}

}  // namespace

Texture resample_texture(const std::vector<Vec3f>& positions, const std::vector<Rgb8>& colors,
                         const std::vector<Vec3f>& normals, const std::vector<float>& radii, const SparseMatrix& psi,
                         const Domains& domains, const SupportRect& rect, const TextureOptions& o, const MeshSurface* surface) {
  double fill = 1;
  Texture tex = resample_at(positions, colors, normals, radii, psi, domains, rect, o, surface, fill);
  if (!(fill < o.sparse_fill) || !(o.min_texel > 0) || !(o.sparse_texel_factor > 1)) return tex;
  TextureOptions coarse = o;  // a sparse quad: texels for the bottom of its level's band
  coarse.min_texel *= o.sparse_texel_factor;
  return resample_at(positions, colors, normals, radii, psi, domains, rect, coarse, surface, fill);
}

}  // namespace qf
