// Render speed (like the paper's table 2 and the thesis' table 5.3): frames per second of every
// method at 128^2, 256^2, 512^2 for each baked level, beside the full point set drawn as splats in
// the same renderer, in the same run. Orbiting camera (the sort order changes every frame), each
// frame finished (glFinish via the readback, which costs 0.005-0.03 ms: gl-notes.md 2).
// usage: qf-bench-render POINTS LEVEL.glb [LEVEL.glb ...]   (scripts/bench.sh render)
#include <chrono>
#include <cstdio>
#include <string>

#include "bench_util.h"
#include "core/memory.h"
#include "runtime_gl/draw_gl11.h"
#include "runtime_gl/egl_context.h"
#include "runtime_gl/loader.h"
#include "measure/reference_scene.h"

using namespace qf;
using namespace qf::render;

namespace {

// Mean ms per frame over at least `seconds` of frames, after 3 warm-up frames (JIT, gl-notes 5.5).
double ms_per_frame(Renderer& r, const Sphere& s, int size, const DrawSettings& settings, double seconds = 0.4) {
  int frame = 0;
  auto one = [&] {
    r.draw(orbit_camera(s, orbit_direction(7.0f * static_cast<float>(frame), 20), 0, size, size), settings);
    r.read_pixels();
    ++frame;
  };
  for (int i = 0; i < 3; ++i) one();
  const auto t0 = std::chrono::steady_clock::now();
  int n = 0;
  double elapsed = 0;
  while (elapsed < seconds || n < 5) {
    one();
    ++n;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return 1000.0 * elapsed / n;
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  if (argc < 3) {
    std::fprintf(stderr, "usage: qf-bench-render POINTS LEVEL.glb [LEVEL.glb ...]\n");
    return 2;
  }
  std::string name;
  PointSet points = bench::load_input(argv[1], 0, name);
  const SplatScene splats = splat_scene(std::move(points), argv[1]);
  const Sphere sphere = bounding_sphere(splats.bounds);
  HeadlessContext context;
  std::printf("renderer: %s\n\n", context.renderer().c_str());
  std::printf("| %-22s | %-13s | %5s | %10s | %10s | %10s | %s |\n", "scene", "method", "quads", "128² fps", "256² fps", "512² fps",
              "speed-up over points (128² / 256² / 512²)");
  std::printf("|---|---|---:|---:|---:|---:|---|\n");
  const int sizes[3] = {128, 256, 512};
  double point_ms[3];
  for (int k = 0; k < 3; ++k) {
    Renderer r(sizes[k], sizes[k]);
    r.set_scene(splats);
    point_ms[k] = ms_per_frame(r, sphere, sizes[k], {});
  }
  std::printf("| %-22s | %-13s | %5zu | %10.1f | %10.1f | %10.1f | 1 |\n", name.c_str(), "splats", splats.positions.size(),
              1000 / point_ms[0], 1000 / point_ms[1], 1000 / point_ms[2]);
  for (int f = 2; f < argc; ++f) {
    const ImpostorScene level = load_gltf(argv[f]);
    std::string file = argv[f];
    file = file.substr(file.find_last_of('/') + 1);
    for (const std::string& m : method_names()) {
      DrawSettings s;
      s.method = method_from_name(m);
      double ms[3];
      for (int k = 0; k < 3; ++k) {
        Renderer r(sizes[k], sizes[k]);
        r.set_scene(level);
        ms[k] = ms_per_frame(r, sphere, sizes[k], s);
      }
      std::printf("| %-22s | %-13s | %5zu | %10.1f | %10.1f | %10.1f | %.1f× / %.1f× / %.1f× |\n", file.c_str(), m.c_str(), level.items.size(),
                  1000 / ms[0], 1000 / ms[1], 1000 / ms[2], point_ms[0] / ms[0], point_ms[1] / ms[1], point_ms[2] / ms[2]);
      std::fflush(stdout);
    }
  }
  return 0;
}
