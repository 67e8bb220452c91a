// Edge-collapse LODs through meshoptimizer (see simplify.h).
#include "simplify/simplify.h"

#include <meshoptimizer.h>

#include <stdexcept>

namespace qf {

SimplifiedMesh simplify_mesh(const TriangleMesh& mesh, std::size_t target_triangles) {
  if (mesh.triangles.empty()) throw std::invalid_argument("simplify_mesh: a mesh without triangles");
  // 1. Collapse: no error bound (the budget decides), so the target error is the whole extent.
  std::vector<unsigned> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const Triangle& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
  std::vector<unsigned> kept(indices.size());
  float relative_error = 0;
  kept.resize(meshopt_simplify(kept.data(), indices.data(), indices.size(), &mesh.positions[0].x, mesh.positions.size(),
                               sizeof(Vec3f), target_triangles * 3, 1.0f, 0, &relative_error));
  // 2. Keep only the vertices still used, in first-use order (meshopt_optimizeVertexFetch's order).
  std::vector<unsigned> remap(mesh.positions.size());
  const std::size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), kept.data(), kept.size(), mesh.positions.size());
  SimplifiedMesh out;
  out.mesh.positions.resize(used);
  if (mesh.colors.size() == mesh.positions.size()) out.mesh.colors.resize(used);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (remap[v] == ~0u) continue;
    out.mesh.positions[remap[v]] = mesh.positions[v];
    if (!out.mesh.colors.empty()) out.mesh.colors[remap[v]] = mesh.colors[v];
  }
  for (std::size_t i = 0; i + 2 < kept.size(); i += 3) out.mesh.triangles.push_back({remap[kept[i]], remap[kept[i + 1]], remap[kept[i + 2]]});
  out.error = relative_error * meshopt_simplifyScale(&mesh.positions[0].x, mesh.positions.size(), sizeof(Vec3f));
  return out;
}

}  // namespace qf
