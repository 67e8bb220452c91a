// Vertex-clustering benchmark (issue 8): the grading + sort once per mesh, then each level's
// clustering and synthesis (single-threaded code), as vertices per second, on model files and on
// a ~1M-triangle sphere mesh. Best of 3 runs.
// usage: qf-bench-cluster MESH... [sphere]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "clustering/clustering.h"
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
  std::printf("%-24s %8s %8s %10s %9s %9s %7s %6s %10s %9s\n", "mesh", "verts", "tris", "cell", "out tris", "edges", "points",
              "ms", "Mverts/s", "grade ms");
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const TriangleMesh m = arg == "sphere" ? generate_mesh("sphere", 354) : read_model(arg).mesh;
    const std::string name = arg == "sphere" ? "sphere (generated)" : arg.substr(arg.find_last_of('/') + 1);
    VertexGrading g;
    const double grade = best_of_3([&] { g = grade_vertices(m); });
    const float diag = m.bounds().diagonal();
    for (float f : {128.f, 32.f, 8.f}) {
      ClusterOptions o;
      o.cell = diag / f;
      LodMesh lod;
      const double s = best_of_3([&] { lod = cluster_mesh(m, g, o); });
      std::printf("%-24s %8zu %8zu %10.4g %9zu %9zu %7zu %6.1f %10.2f %9.1f\n", name.c_str(), m.positions.size(), m.triangles.size(),
                  o.cell, lod.triangles.size(), lod.edges.size(), lod.points.size(), 1e3 * s, m.positions.size() / s / 1e6, 1e3 * grade);
      std::fflush(stdout);
    }
  }
  return 0;
}
