// Mesh sampling benchmark (issue 7, like table 1 of the seed paper): per mesh and LDI size, the
// layers per axis, points produced and the time of the GL and CPU backends, each with the faster
// per-axis variant (the default) and with every triangle on every axis. GL times include making
// the EGL context (~80 ms) and compiling the shaders; the best of 3 runs.
// usage: qf-bench-sample MESH...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "io/model_io.h"
#include "sample/sample.h"

using namespace qf;

int main(int argc, char** argv) {
  std::printf("%-26s %6s %5s %8s %-9s %10s %9s %8s\n", "mesh", "tris", "LDI", "backend", "variant", "layers", "points", "seconds");
  for (int i = 1; i < argc; ++i) {
    const std::string path = argv[i];
    const TriangleMesh mesh = read_model(path).mesh;
    const std::string name = path.substr(path.find_last_of('/') + 1);
    for (int ldi : {100, 1000})
      for (const char* backend : {"gl", "cpu"})
        for (bool per_axis : {true, false}) {
          SampleOptions o;
          o.ldi_size = ldi;
          o.backend = backend;
          o.per_axis_triangles = per_axis;
          double best = 1e30;
          SampleStats st;
          std::size_t n = 0;
          for (int run = 0; run < 3; ++run) {
            const auto t = std::chrono::steady_clock::now();
            n = sample_mesh(mesh, o, path, &st).size();
            best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
          }
          char layers[32];
          std::snprintf(layers, sizeof layers, "%d/%d/%d", st.layers[0], st.layers[1], st.layers[2]);
          std::printf("%-26s %6zu %5d %8s %-9s %10s %9zu %8.3f\n", name.c_str(), mesh.triangles.size(), ldi, st.backend.c_str(),
                      per_axis ? "per-axis" : "all", layers, n, best);
          std::fflush(stdout);
        }
  }
  return 0;
}
