// AMG benchmark (not a test): hierarchy, all basis functions, one level's domains; one input per
// run so that the memory figures are the run's own. scripts/bench.sh prints the table.
// usage: qf-bench-amg --header | SOURCE [points]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "analysis/analysis.h"
#include "bench_util.h"
#include "core/memory.h"
#include "domains/domains.h"
#include "io/model_io.h"
#include "shapes/shapes.h"

using namespace qf;

namespace {


double seconds_since(std::chrono::steady_clock::time_point& t) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  if (argc > 1 && std::string(argv[1]) == "--header") {
    std::printf("| %-14s | %8s | %6s | %10s | %9s | %9s | %8s | %9s | %9s | %9s | %9s |\n", "input", "points", "levels",
                "analysis s", "hierarchy", "all Psi s", "Psi w/pt", "domains s", "end-end s", "A+H B/pt", "Psi B/pt");
    std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(16, '-').c_str(), std::string(10, '-').c_str(),
                std::string(8, '-').c_str(), std::string(12, '-').c_str(), std::string(11, '-').c_str(),
                std::string(11, '-').c_str(), std::string(10, '-').c_str(), std::string(11, '-').c_str(),
                std::string(11, '-').c_str(), std::string(11, '-').c_str(), std::string(11, '-').c_str());
    return 0;
  }
  if (argc < 2) return std::fprintf(stderr, "usage: qf-bench-amg --header | SOURCE [points]\n"), 2;
  std::string name;
  // In Morton order, as the bake hands them to the analysis (pipeline/bake.cpp).
  const PointSet loaded = bench::load_input(argv[1], argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 100000, name);
  const PointSet points = permuted(loaded, morton_order(loaded.positions));
  const std::size_t base = process_memory("VmRSS:");
  auto t = std::chrono::steady_clock::now();
  AmgHierarchy h;
  double t_analysis;
  {
    const SurfaceAnalysis a = analyze_surface(points);
    t_analysis = seconds_since(t);
    h = build_hierarchy(a.stiffness);
  }
  const double t_hierarchy = seconds_since(t);
  const std::size_t peak_ah = process_memory("VmHWM:");
  // One level's domains, as a bake needs: the level nearest 200 functions.
  const std::size_t level = level_by_primitives(h, 200);
  const Domains d = make_domains(basis_at_level(h, level));
  const double t_domains = seconds_since(t);
  // Every level's basis, one after the other.
  double max_weights = 0;
  for_each_basis(h, h.level_count() - 1, {}, [&](std::size_t, const SparseMatrix& psi) {
    max_weights = std::max(max_weights, double(psi.nonZeros()) / double(psi.rows()));
  });
  const double t_basis = seconds_since(t);
  const std::size_t peak = process_memory("VmHWM:");
  std::printf("| %-14s | %8zu | %6zu | %10.3f | %9.3f | %9.3f | %8.1f | %9.3f | %9.3f | %9.0f | %9.0f |\n", name.c_str(),
              points.size(), h.level_count(), t_analysis, t_hierarchy, t_basis, max_weights, t_domains,
              t_analysis + t_hierarchy + t_domains, double(peak_ah - base) / double(points.size()),
              double(peak - base) / double(points.size()));
  (void)d;
  return 0;
}
