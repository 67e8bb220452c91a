// LAS/LAZ writer for tests and benchmarks (see las_writer.h); LAZ through laz-perf's compressors.
#include "las_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "lazperf/lazperf.hpp"
#include "lazperf/vlr.hpp"

namespace qf::test {
namespace {

constexpr std::uint16_t kRecordSize[11] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
constexpr std::uint16_t kRgbOffset[11] = {0, 0, 20, 28, 0, 28, 0, 30, 30, 0, 30};

template <class T>
void put(std::uint8_t* p, T v) {  // little-endian on the machines we build on (x86-64, arm64)
  std::memcpy(p, &v, sizeof v);
}

std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// One record of `format` with extra bytes; the integer coordinates are returned for the bounds.
void encode_record(const LasPoint& p, const LasWriteOptions& o, std::uint64_t index, std::uint8_t* rec, std::int32_t xyz[3]) {
  const int f = o.format;
  std::memset(rec, 0, kRecordSize[f] + o.extra_bytes);
  const double w[3] = {p.x, p.y, p.z};
  for (int a = 0; a < 3; ++a) {
    xyz[a] = static_cast<std::int32_t>(std::llround((w[a] - o.offset[a]) / o.scale[a]));
    put(rec + 4 * a, xyz[a]);
  }
  put(rec + 12, p.intensity);
  if (f < 6) {
    rec[14] = 0x09;  // return 1 of 1
    rec[15] = static_cast<std::uint8_t>(p.classification & 31);
    rec[16] = static_cast<std::uint8_t>(index % 7);  // scan angle rank
    rec[17] = 3;                                      // user data
    put(rec + 18, static_cast<std::uint16_t>(index % 5));
    if (f == 1 || f == 3 || f == 4 || f == 5) put(rec + 20, p.gps_time);
  } else {
    rec[14] = 0x11;  // return 1 of 1
    rec[15] = static_cast<std::uint8_t>(index % 2);  // scanner channel 0/1 in bits 4-5 stays 0
    rec[16] = p.classification;
    rec[17] = 3;
    put(rec + 18, static_cast<std::int16_t>(index % 11));
    put(rec + 20, static_cast<std::uint16_t>(index % 5));
    put(rec + 22, p.gps_time);
    if (f == 8 || f == 10) put(rec + 36, p.nir);
  }
  if (const std::uint16_t c = kRgbOffset[f]) {
    put(rec + c, p.r);
    put(rec + c + 2, p.g);
    put(rec + c + 4, p.b);
  }
  for (std::uint16_t e = 0; e < o.extra_bytes; ++e) rec[kRecordSize[f] + e] = static_cast<std::uint8_t>(index + e);
}

std::uint16_t header_size(int minor) { return minor <= 2 ? 227 : minor == 3 ? 235 : 375; }

std::vector<std::uint8_t> header_bytes(const LasWriteOptions& o, std::uint64_t n, std::uint32_t point_offset,
                                       std::uint32_t vlrs, const double lo[3], const double hi[3]) {
  std::vector<std::uint8_t> h(header_size(o.minor), 0);
  std::memcpy(h.data(), "LASF", 4);
  h[24] = 1, h[25] = static_cast<std::uint8_t>(o.minor);
  std::memcpy(&h[26], o.system_id.data(), std::min<std::size_t>(o.system_id.size(), 32));
  std::memcpy(&h[58], "quasiflat las_writer", 20);
  put(&h[94], header_size(o.minor));
  put(&h[96], point_offset);
  put(&h[100], vlrs);
  h[104] = static_cast<std::uint8_t>(o.format | (o.compress ? 0x80 : 0));
  put(&h[105], static_cast<std::uint16_t>(kRecordSize[o.format] + o.extra_bytes));
  const bool legacy = o.format < 6 && n <= 0xFFFFFFFFull;
  put(&h[107], static_cast<std::uint32_t>(legacy ? n : 0));
  if (legacy) put(&h[111], static_cast<std::uint32_t>(n));  // all first returns
  for (int a = 0; a < 3; ++a) {
    put(&h[131 + 8 * a], o.scale[a]);
    put(&h[155 + 8 * a], o.offset[a]);
    put(&h[179 + 16 * a], hi[a]);
    put(&h[187 + 16 * a], lo[a]);
  }
  if (o.minor >= 4) {
    put(&h[247], n);
    put(&h[255], n);
  }
  return h;
}

}  // namespace

std::uint16_t las_record_size(int format) { return kRecordSize[format]; }

void write_las(std::ostream& out, std::uint64_t n, const std::function<LasPoint(std::uint64_t)>& point, const LasWriteOptions& o) {
  if (o.format < 0 || o.format > 10) throw std::invalid_argument("format");
  if (o.compress && (o.format == 4 || o.format == 5 || o.format >= 9)) throw std::invalid_argument("laz-perf cannot compress this format");
  // 1. The header and VLRs as placeholders (the bounds are known at the end).
  std::vector<std::uint8_t> vlr;
  if (o.compress) {
    const lazperf::laz_vlr laz(o.format, o.extra_bytes, o.chunk_size);
    const std::vector<char> data = laz.data();
    vlr.assign(54, 0);
    std::memcpy(&vlr[2], "laszip encoded", 14);
    put(&vlr[18], static_cast<std::uint16_t>(22204));
    put(&vlr[20], static_cast<std::uint16_t>(data.size()));
    std::memcpy(&vlr[22], "by laz-perf", 11);
    vlr.insert(vlr.end(), data.begin(), data.end());
  }
  const std::uint32_t point_offset = static_cast<std::uint32_t>(header_size(o.minor) + vlr.size());
  const double zero[3] = {0, 0, 0};
  const std::vector<std::uint8_t> blank = header_bytes(o, n, point_offset, o.compress ? 1 : 0, zero, zero);
  out.write(reinterpret_cast<const char*>(blank.data()), static_cast<std::streamsize>(blank.size()));
  out.write(reinterpret_cast<const char*>(vlr.data()), static_cast<std::streamsize>(vlr.size()));
  if (o.compress) out.write("\0\0\0\0\0\0\0\0", 8);  // the chunk table's offset, filled in below

  // 2. The points: raw, or chunk by chunk through laz-perf.
  std::int64_t lo_i[3] = {INT64_MAX, INT64_MAX, INT64_MAX}, hi_i[3] = {INT64_MIN, INT64_MIN, INT64_MIN};
  std::vector<std::uint8_t> rec(kRecordSize[o.format] + o.extra_bytes);
  std::uint64_t written = 0;
  const lazperf::OutputCb sink = [&](const unsigned char* b, std::size_t len) {
    out.write(reinterpret_cast<const char*>(b), static_cast<std::streamsize>(len));
    written += len;
  };
  std::vector<std::uint32_t> chunk_bytes;
  lazperf::las_compressor::ptr compressor;
  for (std::uint64_t i = 0; i < n; ++i) {
    std::int32_t xyz[3];
    encode_record(point(i), o, i, rec.data(), xyz);
    for (int a = 0; a < 3; ++a) lo_i[a] = std::min<std::int64_t>(lo_i[a], xyz[a]), hi_i[a] = std::max<std::int64_t>(hi_i[a], xyz[a]);
    if (!o.compress) {
      out.write(reinterpret_cast<const char*>(rec.data()), static_cast<std::streamsize>(rec.size()));
      continue;
    }
    if (i % o.chunk_size == 0) {
      if (compressor) compressor->done(), chunk_bytes.push_back(static_cast<std::uint32_t>(written)), written = 0;
      compressor = lazperf::build_las_compressor(sink, o.format, o.extra_bytes);
    }
    compressor->compress(reinterpret_cast<const char*>(rec.data()));
  }
  if (compressor) compressor->done(), chunk_bytes.push_back(static_cast<std::uint32_t>(written));

  // 3. LAZ: the chunk table (version 0, count, the arithmetic-coded sizes) and its offset.
  if (o.compress) {
    const std::uint64_t table = static_cast<std::uint64_t>(out.tellp());
    std::uint8_t th[8];
    put(th, std::uint32_t(0));
    put(th + 4, static_cast<std::uint32_t>(chunk_bytes.size()));
    out.write(reinterpret_cast<const char*>(th), 8);
    lazperf::compress_chunk_table(sink, chunk_bytes);
    const std::uint64_t end = static_cast<std::uint64_t>(out.tellp());
    out.seekp(point_offset);
    out.write(reinterpret_cast<const char*>(&table), 8);
    out.seekp(static_cast<std::streamoff>(end));
  }
  // 4. The header again, with the bounds.
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = n ? double(lo_i[a]) * o.scale[a] + o.offset[a] : 0;
    hi[a] = n ? double(hi_i[a]) * o.scale[a] + o.offset[a] : 0;
  }
  const std::uint64_t end = static_cast<std::uint64_t>(out.tellp());
  const std::vector<std::uint8_t> h = header_bytes(o, n, point_offset, o.compress ? 1 : 0, lo, hi);
  out.seekp(0);
  out.write(reinterpret_cast<const char*>(h.data()), static_cast<std::streamsize>(h.size()));
  out.seekp(static_cast<std::streamoff>(end));
}

std::string las_bytes(const std::vector<LasPoint>& points, const LasWriteOptions& options) {
  std::ostringstream s;
  write_las(s, points.size(), [&](std::uint64_t i) { return points[i]; }, options);
  return s.str();
}

LasPoint random_las_point(std::uint64_t i, std::uint32_t seed, const double centre[3], double extent) {
  const std::uint64_t h = splitmix(splitmix(seed) ^ i), h2 = splitmix(h);
  const double u = double(h >> 11) * 0x1p-53, v = double(h2 >> 11) * 0x1p-53;
  LasPoint p;
  p.x = centre[0] + (u - 0.5) * extent;
  p.y = centre[1] + (v - 0.5) * extent;
  p.z = centre[2] + 0.05 * extent * std::sin(6.283185307179586 * u) * std::cos(6.283185307179586 * v);
  p.r = static_cast<std::uint16_t>(h2 >> 48), p.g = static_cast<std::uint16_t>(h2 >> 32), p.b = static_cast<std::uint16_t>(h2 >> 16);
  p.nir = static_cast<std::uint16_t>(h);
  p.classification = static_cast<std::uint8_t>((h >> 3) % 32);
  p.intensity = static_cast<std::uint16_t>(h >> 20);
  p.gps_time = 1000.0 + 0.001 * double(i);
  return p;
}

std::vector<LasPoint> random_las_points(std::size_t n, std::uint32_t seed, const double centre[3], double extent) {
  std::vector<LasPoint> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = random_las_point(i, seed, centre, extent);
  return v;
}

}  // namespace qf::test
