// The Voronoi-clipping fans equal the 1-rings of CGAL's 2D Delaunay triangulation of the same
// projected neighbourhoods (the design card's tool), on generated shapes and on real models.
// CGAL is used here only, as the oracle.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "analysis/analysis.h"
#include "io/model_io.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::int64_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;

// CGAL's fan of point i: triangles (a, b) counter-clockwise around i, from the Delaunay
// triangulation of i and its neighbours projected as compute_fans projects them. Neighbours that
// project onto i itself are left out, as compute_fans does.
std::set<std::array<std::uint32_t, 2>> cgal_fan(std::size_t i, const std::vector<Vec3f>& pos, const Neighborhoods& nb,
                                                const LocalFrames& f) {
  std::vector<std::pair<Kernel::Point_2, std::int64_t>> pts;
  pts.push_back({Kernel::Point_2(0, 0), -1});
  for (std::uint32_t r = nb.offsets[i]; r < nb.offsets[i + 1]; ++r) {
    const Vec3f d = pos[nb.indices[r]] - pos[i];
    const double u = double(d.x) * f.e0[i].x + double(d.y) * f.e0[i].y + double(d.z) * f.e0[i].z;
    const double v = double(d.x) * f.e1[i].x + double(d.y) * f.e1[i].y + double(d.z) * f.e1[i].z;
    if (u == 0 && v == 0) continue;
    pts.push_back({Kernel::Point_2(u, v), nb.indices[r]});
  }
  Delaunay dt;
  dt.insert(pts.begin(), pts.end());
  std::set<std::array<std::uint32_t, 2>> fan;
  Delaunay::Vertex_handle center;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    if (v->info() == -1) center = v;
  if (center == Delaunay::Vertex_handle() || dt.dimension() < 2) return fan;
  auto face = dt.incident_faces(center), done = face;
  do {
    if (!dt.is_infinite(face)) {
      const int c = face->index(center);
      fan.insert({static_cast<std::uint32_t>(face->vertex(Delaunay::ccw(c))->info()),
                  static_cast<std::uint32_t>(face->vertex(Delaunay::cw(c))->info())});
    }
  } while (++face != done);
  return fan;
}

struct Comparison {
  std::size_t points = 0, same = 0;
};

Comparison compare_with_cgal(const PointSet& p, std::size_t stride) {
  const SurfaceAnalysis a = analyze_surface(p);
  Comparison c;
  for (std::size_t i = 0; i < p.size(); i += stride) {
    std::set<std::array<std::uint32_t, 2>> ours(a.fans.triangles.begin() + a.fans.offsets[i],
                                                a.fans.triangles.begin() + a.fans.offsets[i + 1]);
    ++c.points;
    c.same += ours == cgal_fan(i, p.positions, a.neighborhoods, a.frames);
  }
  return c;
}

TEST(FansVsCgal, GeneratedShapes) {
  for (const char* shape : {"sphere", "torus", "octahedron", "crease"}) {
    const Comparison c = compare_with_cgal(generate_shape(shape, {20000, 11}), 7);
    // Random samples have no exactly cocircular neighbours: every fan must agree.
    EXPECT_EQ(c.same, c.points) << shape;
    std::printf("[ fans     ] %-10s %zu of %zu fans identical to CGAL's\n", shape, c.same, c.points);
  }
}

TEST(FansVsCgal, RealModels) {
  const char* env = std::getenv("QF_MODELS");
  const std::string dir = env ? env : std::string(std::getenv("HOME") ? std::getenv("HOME") : "") + "/.cache/quasiflat/models";
  if (!std::filesystem::exists(dir + "/bunny00.off")) GTEST_SKIP() << "models not fetched (scripts/fetch-models.sh)";
  for (const char* name : {"bunny00.off", "fandisk.off", "kitten.xyz", "ball.ply"}) {
    const Model m = read_model(dir + "/" + name);
    PointSet p;
    if (m.is_mesh) p.positions = m.mesh.positions;
    else p = m.points;
    const Comparison c = compare_with_cgal(p, 5);
    std::printf("[ fans     ] %-10s %zu of %zu fans identical to CGAL's\n", name, c.same, c.points);
    // Scanned and meshed data can hold exactly cocircular neighbours (grids), where either
    // triangulation is right; at most 1% may differ.
    EXPECT_GE(c.same, c.points * 99 / 100) << name;
  }
}

}  // namespace
}  // namespace qf
