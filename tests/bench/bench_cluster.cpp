// Vertex-clustering benchmark (issue 8): the grading + sort once per mesh, then each level's
// clustering and synthesis (single-threaded), as vertices per second, beside meshoptimizer's
// meshopt_simplifySloppy (also vertex clustering, on a uniform grid) asked for the same number of
// triangles. Best of 3 runs. With --write DIR, each level is written as DIR/NAME_dK_ours.glb and
// DIR/NAME_dK_meshopt.ply for `qf-render eval` (scripts/bench.sh cluster does that).
// usage: qf-bench-cluster [--write DIR] MESH|sphere...
#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

#include "clustering/clustering.h"
#include "core/memory.h"
#include "gltf/glb.h"
#include "io/model_io.h"
#include "shapes/shapes.h"

using namespace qf;

template <class F>
double best_of_3(F f) {
  double best = 1e30;
  for (int i = 0; i < 3; ++i) {
    const auto t = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
  }
  return best;
}

int main(int argc, char** argv) {
  keep_freed_memory();  // as qf-bake does: freed memory is reused, not faulted in again per level
  std::string dir;
  std::printf("%-22s %8s %8s %6s %9s %6s %7s %9s | %9s %7s %9s\n", "mesh", "verts", "tris", "cell", "our tris", "edges", "ms",
              "Mverts/s", "meshopt", "ms", "Mverts/s");
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--write" && i + 1 < argc) {
      dir = argv[++i];
      continue;
    }
    const TriangleMesh m = arg == "sphere" ? generate_mesh("sphere", 354) : read_model(arg).mesh;
    const std::string name = arg == "sphere" ? "sphere1M" : arg.substr(arg.find_last_of('/') + 1, arg.find_last_of('.') - arg.find_last_of('/') - 1);
    VertexGrading g;
    const double grade = best_of_3([&] { g = grade_vertices(m); });
    std::vector<unsigned> indices;
    for (const Triangle& t : m.triangles) indices.insert(indices.end(), {t[0], t[1], t[2]});
    const float diag = m.bounds().diagonal();
    for (int f : {128, 32, 8}) {
      ClusterOptions o;
      o.cell = diag / static_cast<float>(f);
      LodMesh lod;
      const double ours = best_of_3([&] { lod = cluster_mesh(m, g, o); });
      std::vector<unsigned> out(indices.size());
      std::size_t n = 0;
      const double theirs = best_of_3([&] {
        n = meshopt_simplifySloppy(out.data(), indices.data(), indices.size(), &m.positions[0].x, m.positions.size(), sizeof(Vec3f),
                                   lod.triangles.size() * 3, 1.0f, nullptr);
      });
      std::printf("%-22s %8zu %8zu %6s %9zu %6zu %7.1f %9.2f | %9zu %7.1f %9.2f\n", name.c_str(), m.positions.size(), m.triangles.size(),
                  ("d/" + std::to_string(f)).c_str(), lod.triangles.size(), lod.edges.size(), 1e3 * ours, m.positions.size() / ours / 1e6,
                  n / 3, 1e3 * theirs, m.positions.size() / theirs / 1e6);
      std::fflush(stdout);
      if (!dir.empty()) {
        const std::string stem = dir + "/" + name + "_d" + std::to_string(f);
        const std::vector<std::uint8_t> glb = encode_cluster_glb(lod);
        std::ofstream(stem + "_ours.glb", std::ios::binary).write(reinterpret_cast<const char*>(glb.data()), static_cast<std::streamsize>(glb.size()));
        TriangleMesh simple;
        simple.positions = m.positions;
        simple.colors = m.colors;
        for (std::size_t k = 0; k + 2 < n; k += 3) simple.triangles.push_back({out[k], out[k + 1], out[k + 2]});
        write_ply(stem + "_meshopt.ply", simple);
      }
    }
    std::printf("%-22s grading + sort: %.1f ms (once per mesh)\n", name.c_str(), 1e3 * grade);
  }
  return 0;
}
