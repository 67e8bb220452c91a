// Surface analysis benchmark (not a test): one configuration per run, one table row, so that each
// row's peak memory is its own: B/pt = (peak resident memory - resident memory before the
// analysis) / points, i.e. what the analysis itself needs. The peer, in the same run and with the
// same k and threads: PCL's NormalEstimationOMP (kd-tree build + kNN + PCA normals, nothing else),
// the standard normal estimation, which does a fraction of our work (no fans, no matrix); "vs PCL"
// = PCL's time / ours (1 = as fast as PCL's normals alone). Both are run `reps` times alternately
// and the fastest of each is shown, which tames the noise of a shared machine. scripts/bench.sh
// runs the table.
// usage: qf-bench-analysis --header
//        qf-bench-analysis SOURCE [points] [k] [reps]
//   SOURCE: a shape name (torus, sphere, ...) or a model file (mesh vertices are used as points)
#include <omp.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
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

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// PCL's normal estimation as its users run it: a KdTree search, setKSearch(k), every thread
// (NormalEstimationOMP with omp_get_max_threads()). The cloud conversion is not timed.
double pcl_normals_seconds(const PointSet& points, int k) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    (*cloud)[i] = pcl::PointXYZ(points.positions[i].x, points.positions[i].y, points.positions[i].z);
  pcl::PointCloud<pcl::Normal> normals;
  const auto t0 = std::chrono::steady_clock::now();
  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> ne(static_cast<unsigned>(omp_get_max_threads()));
  ne.setInputCloud(cloud);
  ne.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  ne.setKSearch(k);
  ne.compute(normals);
  return seconds_since(t0);
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  if (argc > 1 && std::string(argv[1]) == "--header") {
    std::printf("| %-22s | %9s | %3s | %7s | %7s | %7s | %8s | %7s | %7s | %7s | %7s | %9s | %9s | %6s | %7s | %7s |\n", "input",
                "points", "k", "threads", "nbhd s", "frame s", "orient s", "class s", "fans s", "A s", "total s", "points/s", "B/pt",
                "fan", "PCL s", "vs PCL");
    for (int width : {24, 11, 5, 9, 9, 9, 10, 9, 9, 9, 9, 11, 11, 8, 9, 9}) std::printf("|%s", std::string(width, '-').c_str());
    std::printf("|\n");
    return 0;
  }
  if (argc < 2) {
    std::fprintf(stderr, "usage: qf-bench-analysis --header | SOURCE [points] [k] [reps]\n");
    return 2;
  }
  AnalysisOptions o;
  o.neighborhoods.k = argc > 3 ? std::atoi(argv[3]) : 50;
  std::string name;
  // In Morton order, as the bake hands them to the analysis (pipeline/bake.cpp); PCL gets the same.
  const PointSet loaded = bench::load_input(argv[1], argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 100000, name);
  const PointSet points = permuted(loaded, morton_order(loaded.positions));
  const int reps = argc > 4 ? std::max(1, std::atoi(argv[4])) : 3;
  const std::size_t before = process_memory("VmRSS:");  // libraries and the input point set
  double total = 1e30, t[6] = {0, 0, 0, 0, 0, 0}, pcl_best = 1e30, fan = 0;
  std::size_t peak = 0;
  for (int rep = 0; rep < reps; ++rep) {
    {
      const SurfaceAnalysis a = analyze_surface(points, o);
      if (rep == 0) peak = process_memory("VmHWM:");  // the analysis' own peak, before PCL runs
      double sum = 0;
      for (const StepTime& s : a.report.times) sum += s.seconds;
      if (sum < total) {
        total = sum;
        for (std::size_t s = 0; s < a.report.times.size() && s < 6; ++s) t[s] = a.report.times[s].seconds;
      }
      fan = a.report.mean_fan_size;
    }
    pcl_best = std::min(pcl_best, pcl_normals_seconds(points, o.neighborhoods.k));
  }
  std::printf("| %-22s | %9zu | %3d | %7d | %7.3f | %7.3f | %8.3f | %7.3f | %7.3f | %7.3f | %7.3f | %9.0f | %9.0f | %6.2f | %7.3f | %7.2f |\n",
              name.c_str(), points.size(), o.neighborhoods.k, omp_get_max_threads(), t[0], t[1], t[2], t[3], t[4], t[5], total,
              points.size() / total, double(peak - before) / double(points.size()), fan, pcl_best, pcl_best / total);
  return 0;
}
