// Reader throughput benchmark: prints a table (not a test). Targets from the foundation issue:
// binary PLY >= 300 MB/s, ascii PLY >= 40 MB/s, QSplat decoding >= 10M leaves/s.
// usage: qf-bench-io [points=1000000] [repeats=5]
#include <charconv>
#include <functional>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/file_io.h"
#include "core/memory.h"
#include "io/model_io.h"
#include "shapes/shapes.h"

using namespace qf;

namespace {

// Best time over `repeats` runs; `first` gets the first run's (fresh output memory: page faults).
double best_seconds(int repeats, const std::function<std::size_t()>& run, std::size_t& count, double& first) {
  double best = 1e30;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    count = run();
    const auto t1 = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(t1 - t0).count();
    if (r == 0) first = s;
    best = std::min(best, s);
  }
  return best;
}

void write_ascii_ply(const std::string& path, const PointSet& p) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat ascii 1.0\nelement vertex " << p.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
         "property float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  std::string line;
  char buf[32];
  for (std::size_t i = 0; i < p.size(); ++i) {
    line.clear();
    for (float v : {p.positions[i].x, p.positions[i].y, p.positions[i].z, p.normals[i].x, p.normals[i].y, p.normals[i].z}) {
      line.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
      line += ' ';
    }
    line += std::to_string(p.colors[i].r) + ' ' + std::to_string(p.colors[i].g) + ' ' + std::to_string(p.colors[i].b) + '\n';
    out << line;
  }
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  const std::string dir = (std::filesystem::temp_directory_path() / "qf-bench-io").string();
  std::filesystem::create_directories(dir);

  ShapeOptions o;
  o.points = n;
  PointSet p = generate_shape("torus", o);  // normals, colours and radii
  PointSet no_radii = p;
  no_radii.radii.clear();
  write_ply(dir + "/bin.ply", no_radii);
  write_ascii_ply(dir + "/ascii.ply", no_radii);
  write_point_set(dir + "/points.qs", p);

  struct Row {
    const char* name;
    std::string file;
    const char* unit;
    double target;
  };
  const Row rows[] = {{"ply binary_little_endian (xyz, normal, rgb)", dir + "/bin.ply", "MB/s", 300},
                      {"ply ascii (xyz, normal, rgb)", dir + "/ascii.ply", "MB/s", 40},
                      {"qsplat decode (colour)", dir + "/points.qs", "Mleaves/s", 10}};
  std::printf("reader benchmark: %zu points, best of %d runs (mapping the file from the page cache included;\n"
              "the first run also pays the page faults of fresh output memory)\n\n", n, repeats);
  std::printf("| %-44s | %8s | %9s | %8s | %9s | %18s | %3s |\n", "input", "size MB", "first ms", "best ms",
              "Mpoints/s", "rate (target)", "ok");
  std::printf("|%s|%s|%s|%s|%s|%s|%s|\n", std::string(46, '-').c_str(), std::string(10, '-').c_str(),
              std::string(11, '-').c_str(), std::string(10, '-').c_str(), std::string(11, '-').c_str(),
              std::string(20, '-').c_str(), std::string(5, '-').c_str());
  bool all_ok = true;
  for (const Row& r : rows) {
    const double mb = static_cast<double>(std::filesystem::file_size(r.file)) / 1e6;
    std::size_t count = 0;
    double first = 0;
    const double s = best_seconds(repeats, [&] { return read_model(r.file).points.size(); }, count, first);
    const double rate = std::string(r.unit) == "MB/s" ? mb / s : count / s / 1e6;
    const bool ok = rate >= r.target && count == p.size();
    all_ok = all_ok && ok;
    char rate_text[64];
    std::snprintf(rate_text, sizeof rate_text, "%.0f %s (%.0f)", rate, r.unit, r.target);
    std::printf("| %-44s | %8.1f | %9.1f | %8.1f | %9.2f | %18s | %3s |\n", r.name, mb, first * 1e3, s * 1e3,
                count / s / 1e6, rate_text, ok ? "yes" : "NO");
  }
  std::filesystem::remove_all(dir);
  return all_ok ? 0 : 1;
}
