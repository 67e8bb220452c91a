// The only file that includes CGAL's reconstruction headers.
#include "reconstruct/reconstruct.h"

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Random.h>
#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/deterministic_heap.h"

namespace qf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// 1. The points to use: all, or every k-th of the Morton order (an even spread over the set, as
// the order walks the set cell by cell).
std::vector<std::uint32_t> spread_subsample(const PointSet& points, std::size_t max_points) {
  std::vector<std::uint32_t> order = morton_order(points.positions);
  if (order.size() <= max_points || max_points == 0) return order;
  std::vector<std::uint32_t> kept;
  kept.reserve(max_points);
  const double step = double(order.size()) / double(max_points);
  for (std::size_t i = 0; i < max_points; ++i) kept.push_back(order[static_cast<std::size_t>(double(i) * step)]);
  return kept;
}

}  // namespace

Reconstruction reconstruct_surface(const PointSet& points, const ReconstructOptions& o) {
  Reconstruction r;
  const std::vector<std::uint32_t> used = spread_subsample(points, o.max_points);
  if (used.size() < 4) throw std::invalid_argument("a reconstruction needs at least 4 points");
  // 2. Advancing front over the 3D Delaunay triangulation of the points (CGAL's defaults: radius
  // ratio bound 5, beta 0.52): facets as triples of indices into `cgal_points`.
  std::vector<Kernel::Point_3> cgal_points;
  cgal_points.reserve(used.size());
  for (std::uint32_t i : used) cgal_points.emplace_back(points.positions[i].x, points.positions[i].y, points.positions[i].z);
  std::vector<std::array<std::size_t, 3>> facets;
  // The triangulation's insertion order is shuffled by CGAL's default random generator, which is
  // seeded from the clock: a fixed seed makes the same points give the same mesh on every run.
  CGAL::get_default_random() = CGAL::Random(0);
  {
    // The front orders its candidates by (priority, address): equal radii (a symmetric set such
    // as the generated torus) and the constant stand-by priorities tie. The reconstruction runs in
    // a heap of its own, so those addresses, and the mesh, do not depend on the process's earlier
    // allocations (oni.pwn's mesh differed between 1 and 2 threads, a generated torus's between a
    // batch's -j). The facets are kept on the process heap. Its reserve: the front used 2.2 KB a
    // point (110.8 MB for 50,000 of a generated scan, 3.5 MB for oni.pwn's 1,435); 64 KB a point
    // leaves room for far worse triangulations, as address space only.
    DeterministicHeap heap((std::size_t{256} << 20) + cgal_points.size() * (std::size_t{64} << 10));
    try {
      CGAL::advancing_front_surface_reconstruction(
          cgal_points.begin(), cgal_points.end(), boost::make_function_output_iterator([&](const std::array<std::size_t, 3>& f) {
            DeterministicHeap::Pause outside;
            facets.push_back(f);
          }));
    } catch (const std::bad_alloc&) {
      DeterministicHeap::Pause outside;
      throw std::invalid_argument("the reconstruction outgrew its reserve of " + std::to_string(heap.reserve_bytes() >> 20) + " MB");
    } catch (const std::exception& e) {
      // CGAL's failures carry strings allocated in the scope's region: their message is copied
      // out before the region goes.
      DeterministicHeap::Pause outside;
      throw std::invalid_argument(std::string("CGAL's advancing front failed: ") + e.what());
    }
  }
  if (facets.empty()) throw std::invalid_argument("the points form no surface to reconstruct");
  // 3. The mesh: the used points as vertices, their colours carried.
  r.points_used = used.size();
  r.mesh.positions.reserve(used.size());
  for (std::uint32_t i : used) r.mesh.positions.push_back(points.positions[i]);
  if (points.has_colors()) {
    r.mesh.colors.reserve(used.size());
    for (std::uint32_t i : used) r.mesh.colors.push_back(points.colors[i]);
  }
  // In a canonical order (each triangle from its smallest index, orientation kept; then sorted):
  // the front emits its facets in an order that follows memory addresses.
  r.mesh.triangles.reserve(facets.size());
  for (const auto& f : facets) {
    Triangle t{static_cast<std::uint32_t>(f[0]), static_cast<std::uint32_t>(f[1]), static_cast<std::uint32_t>(f[2])};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    r.mesh.triangles.push_back(t);
  }
  std::sort(r.mesh.triangles.begin(), r.mesh.triangles.end());
  return r;
}

}  // namespace qf
