// Surface analysis benchmark (not a test): one configuration per run, one table row, so that each
// row's peak memory is its own: B/pt = (peak resident memory - resident memory before the
// analysis) / points, i.e. what the analysis itself needs. scripts/bench.sh runs the table.
// usage: qf-bench-analysis --header
//        qf-bench-analysis SOURCE [points] [k]
//   SOURCE: a shape name (torus, sphere, ...) or a model file (mesh vertices are used as points)
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "analysis/analysis.h"
#include "bench_util.h"
#include "core/memory.h"
#include "io/model_io.h"
#include "shapes/shapes.h"

using namespace qf;

namespace {


}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  if (argc > 1 && std::string(argv[1]) == "--header") {
    std::printf("| %-22s | %9s | %3s | %7s | %7s | %7s | %7s | %7s | %7s | %7s | %9s | %9s | %6s |\n", "input", "points",
                "k", "threads", "nbhd s", "frame s", "class s", "fans s", "A s", "total s", "points/s", "B/pt",
                "fan");
    std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(24, '-').c_str(), std::string(11, '-').c_str(),
                std::string(5, '-').c_str(), std::string(9, '-').c_str(), std::string(9, '-').c_str(),
                std::string(9, '-').c_str(), std::string(9, '-').c_str(), std::string(9, '-').c_str(),
                std::string(9, '-').c_str(), std::string(9, '-').c_str(), std::string(11, '-').c_str(),
                std::string(11, '-').c_str(), std::string(8, '-').c_str());
    return 0;
  }
  if (argc < 2) {
    std::fprintf(stderr, "usage: qf-bench-analysis --header | SOURCE [points] [k]\n");
    return 2;
  }
  AnalysisOptions o;
  o.neighborhoods.k = argc > 3 ? std::atoi(argv[3]) : 50;
  std::string name;
  const PointSet points = bench::load_input(argv[1], argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 100000, name);
  const std::size_t before = process_memory("VmRSS:");  // libraries and the input point set
  const SurfaceAnalysis a = analyze_surface(points, o);
  const std::size_t peak = process_memory("VmHWM:");
  double total = 0, t[5] = {0, 0, 0, 0, 0};
  for (std::size_t s = 0; s < a.report.times.size() && s < 5; ++s) t[s] = a.report.times[s].seconds, total += t[s];
  std::printf("| %-22s | %9zu | %3d | %7d | %7.3f | %7.3f | %7.3f | %7.3f | %7.3f | %7.3f | %9.0f | %9.0f | %6.2f |\n",
              name.c_str(), points.size(), o.neighborhoods.k, omp_get_max_threads(), t[0], t[1], t[2], t[3], t[4], total,
              points.size() / total, double(peak - before) / double(points.size()), a.report.mean_fan_size);
  return 0;
}
