// LAS/LAZ reading speed (issue 35): writes a seeded airborne-scan-like point set as LAS or LAZ,
// or reads one with read_model (whole) or stream_point_set (in blocks, as a bake out of core reads
// it) and prints seconds, points/s and the process's peak RSS.
//   qf-bench-las write OUT.las|OUT.laz N FORMAT [MINOR]   (LAZ by extension; formats 0-3, 6-8 for LAZ)
//   qf-bench-las read|stream FILE                         (run it in a fresh process: the RSS is its own)
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/file_io.h"
#include "io/model_io.h"
#include "../unit/io/las_writer.h"

namespace {

// Scan lines of sqrt(n) points 0.1 m apart, back and forth, 0.5 m between lines, in UTM
// coordinates over a rolling terrain: neighbouring records are neighbouring points, as in real
// airborne scans (LAZ's predictors rely on that). Colours over 16 bits, classes 1-6.
qf::test::LasPoint scan_point(std::uint64_t i, std::uint64_t n) {
  const std::uint64_t per_line = std::max<std::uint64_t>(1, std::uint64_t(std::sqrt(double(n)))), line = i / per_line, k = i % per_line;
  const double along = (line % 2 ? double(per_line - 1 - k) : double(k)) * 0.1;
  qf::test::LasPoint p;
  p.x = 512000.0 + along + 0.013 * double((i * 2654435761u) % 7);
  p.y = 4100000.0 + double(line) * 0.5;
  p.z = 250.0 + 8.0 * std::sin(p.x * 0.01) * std::cos(p.y * 0.013) + 0.02 * double(i % 5);
  p.r = static_cast<std::uint16_t>(30000 + 20000 * std::sin(p.x * 0.05));
  p.g = static_cast<std::uint16_t>(30000 + 20000 * std::cos(p.y * 0.05));
  p.b = static_cast<std::uint16_t>(20000 + 256 * (i % 17));
  p.classification = static_cast<std::uint8_t>(1 + (i / 97) % 6);
  p.intensity = static_cast<std::uint16_t>(400 + (i * 7) % 300);
  p.gps_time = 300000.0 + double(i) * 1e-5;
  return p;
}

long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "write" && (argc == 5 || argc == 6)) {
    const std::string out = argv[2];
    qf::test::LasWriteOptions o;
    o.format = std::stoi(argv[4]);
    o.minor = argc == 6 ? std::stoi(argv[5]) : (o.format >= 6 ? 4 : 2);
    o.compress = qf::file_extension(out) == "laz";
    o.scale[0] = o.scale[1] = o.scale[2] = 0.001;
    o.offset[0] = 500000, o.offset[1] = 4100000, o.offset[2] = 0;
    std::ofstream f(out, std::ios::binary);
    const std::uint64_t n = std::stoull(argv[3]);
    qf::test::write_las(f, n, [n](std::uint64_t i) { return scan_point(i, n); }, o);
    return f.good() ? 0 : 1;
  }
  if ((mode == "read" || mode == "stream") && argc == 3) {
    // read: the whole set in memory (read_model); stream: what a bake out of core does with a
    // LAS/LAZ file, blocks of 65,536 points, none kept.
    const auto t0 = std::chrono::steady_clock::now();
    qf::ReadReport report;
    std::size_t points = 0;
    if (mode == "read") points = qf::read_model(argv[2], {}, &report).points.size();
    else qf::stream_point_set(argv[2], {}, &report, 65536, [&points](qf::PointSet& block) { points += block.size(); });
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-32s %-30s %10zu points %7.3f s %6.2f M points/s  peak RSS %6.1f MB  (%s)\n", argv[2], report.format.c_str(),
                points, s, double(points) / s / 1e6, double(peak_rss_kb()) / 1024.0, mode == "read" ? "whole" : "streamed");
    return 0;
  }
  std::fprintf(stderr, "usage: qf-bench-las write OUT.las|OUT.laz N FORMAT [MINOR] | read FILE | stream FILE\n");
  return 2;
}
