// A LAS/LAZ writer for tests and benchmarks: any point data format 0–10 in LAS 1.0–1.4, with extra
// bytes, and LAZ (formats 0–3, 6–8) compressed with laz-perf's chunk compressors. Not a product
// writer: it exists so that the reader can be tested on files whose every value is known.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace qf::test {

struct LasPoint {
  double x = 0, y = 0, z = 0;  // world coordinates; stored as round((x - offset) / scale)
  std::uint16_t r = 0, g = 0, b = 0, nir = 0;
  std::uint8_t classification = 0;  // formats 0–5 keep its low 5 bits
  std::uint16_t intensity = 0;
  double gps_time = 0;
};

struct LasWriteOptions {
  int minor = 2;                // LAS 1.minor (0..4); the header's size follows it
  int format = 3;               // point data format 0..10
  std::uint16_t extra_bytes = 0;  // past the format's record (filled with a known pattern)
  double scale[3] = {0.001, 0.001, 0.001};
  double offset[3] = {0, 0, 0};
  bool compress = false;        // LAZ (laz-perf), formats 0–3 and 6–8
  std::uint32_t chunk_size = 50000;
  std::string system_id = "quasiflat test";
};

// Writes n points (point(i) for i = 0..n-1) as LAS or LAZ to `out`, which must be seekable (the
// header's bounds, and LAZ's chunk table offset, are filled in at the end).
void write_las(std::ostream& out, std::uint64_t n, const std::function<LasPoint(std::uint64_t)>& point,
               const LasWriteOptions& options);

// The same into a string.
std::string las_bytes(const std::vector<LasPoint>& points, const LasWriteOptions& options);

// Seeded points on a wavy sheet: x, y in [cx - extent/2, cx + extent/2], colours over 16 bits,
// classes 0..31, intensities and GPS times; the same seed gives the same points.
std::vector<LasPoint> random_las_points(std::size_t n, std::uint32_t seed, const double centre[3], double extent);
LasPoint random_las_point(std::uint64_t i, std::uint32_t seed, const double centre[3], double extent);

// The record's size of each format (without extra bytes).
std::uint16_t las_record_size(int format);

}  // namespace qf::test
