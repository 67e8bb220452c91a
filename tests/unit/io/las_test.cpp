// LAS/LAZ reader: every point format's positions (scale and offset applied), colours and classes
// against the values written; LAZ against the LAS it was made from; the origin of georeferenced
// files; malformed headers, VLRs, chunk tables and chunks each refused with their code.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/error.h"
#include "io/model_io.h"
#include "las_writer.h"
#include "test_util.h"

namespace qf {
namespace {

using test::LasPoint;
using test::LasWriteOptions;

const double kCentre[3] = {10.0, -20.0, 5.0};

// The LAS reader itself (read_model's dispatch by extension is checked by the CLI tests), so that
// this file builds with the reader and laz-perf alone for a quick sanitizer run.
PointSet decode(const std::string& bytes, const std::string& name, ReadReport* report = nullptr) {
  const ByteView v(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  return decode_las(v, name, {}, report);
}

std::string error_code(const std::string& bytes, const std::string& name = "bad.las") {
  try {
    decode(bytes, name);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), name);
    EXPECT_FALSE(e.where().empty()) << e.what();
    return e.code();
  }
  return "accepted";
}

bool has_rgb(int format) { return format == 2 || format == 3 || format == 5 || format == 7 || format == 8 || format == 10; }

// Checks what was read against the points written: positions to the float nearest the scaled
// integer (minus the origin), classes, and colours as the reader's 16-to-8-bit rule gives them.
void expect_points(const PointSet& got, const std::vector<LasPoint>& want, const LasWriteOptions& o, const double origin[3]) {
  ASSERT_EQ(got.size(), want.size());
  ASSERT_EQ(got.scalars.size(), 1u);
  EXPECT_EQ(got.scalars[0].name, "classification");
  ASSERT_EQ(got.has_colors(), has_rgb(o.format));
  for (std::size_t i = 0; i < want.size(); ++i) {
    const double w[3] = {want[i].x, want[i].y, want[i].z};
    for (int a = 0; a < 3; ++a) {
      const double stored = double(std::llround((w[a] - o.offset[a]) / o.scale[a])) * o.scale[a] + (o.offset[a] - origin[a]);
      ASSERT_EQ(got.positions[i][a], static_cast<float>(stored)) << "point " << i << " axis " << a;
    }
    const int cls = o.format < 6 ? (want[i].classification & 31) : want[i].classification;
    ASSERT_EQ(got.scalars[0].values[i], float(cls)) << i;
    if (has_rgb(o.format)) {
      const Rgb8 c{std::uint8_t(want[i].r >> 8), std::uint8_t(want[i].g >> 8), std::uint8_t(want[i].b >> 8)};
      ASSERT_TRUE(got.colors[i] == c) << i;
    }
  }
}

struct FormatCase {
  int minor, format;
};

TEST(Las, EveryPointFormatAndVersion) {
  const double none[3] = {0, 0, 0};
  const std::vector<LasPoint> pts = test::random_las_points(300, 7, kCentre, 50.0);
  for (const FormatCase c : {FormatCase{0, 0}, {1, 1}, {2, 0}, {2, 1}, {2, 2}, {2, 3}, {3, 4}, {3, 5},
                             {4, 0}, {4, 3}, {4, 6}, {4, 7}, {4, 8}, {4, 9}, {4, 10}}) {
    SCOPED_TRACE("LAS 1." + std::to_string(c.minor) + " format " + std::to_string(c.format));
    LasWriteOptions o;
    o.minor = c.minor, o.format = c.format;
    o.scale[0] = 0.01, o.scale[1] = 0.002, o.scale[2] = 0.0005;
    o.offset[0] = 3.5, o.offset[1] = -7.25, o.offset[2] = 1.0;
    ReadReport report;
    const PointSet got = decode(test::las_bytes(pts, o), "f.las", &report);
    expect_points(got, pts, o, none);
    EXPECT_EQ(report.format, "las 1." + std::to_string(c.minor) + " (point format " + std::to_string(c.format) + ")");
    EXPECT_TRUE(got.comments.empty()) << "no origin needed for coordinates this small";
  }
}

TEST(Las, ExtraBytesPastTheRecordAreSkipped) {
  const double none[3] = {0, 0, 0};
  const std::vector<LasPoint> pts = test::random_las_points(200, 3, kCentre, 10.0);
  for (const bool laz : {false, true})
    for (const int format : {1, 3, 6, 7}) {
      SCOPED_TRACE(std::to_string(format) + (laz ? " laz" : " las"));
      LasWriteOptions o;
      o.minor = 4, o.format = format, o.extra_bytes = 5, o.compress = laz, o.chunk_size = 64;
      expect_points(decode(test::las_bytes(pts, o), laz ? "e.laz" : "e.las"), pts, o, none);
    }
}

TEST(Las, LazReadsTheSamePointsAsItsLas) {
  // Several chunks, the last one short; every format laz-perf compresses.
  const std::vector<LasPoint> pts = test::random_las_points(2500, 11, kCentre, 80.0);
  for (const FormatCase c : {FormatCase{2, 0}, {2, 1}, {2, 2}, {2, 3}, {4, 6}, {4, 7}, {4, 8}}) {
    SCOPED_TRACE("format " + std::to_string(c.format));
    LasWriteOptions o;
    o.minor = c.minor, o.format = c.format, o.chunk_size = 1000;
    const PointSet las = decode(test::las_bytes(pts, o), "p.las");
    o.compress = true;
    const std::string laz_bytes = test::las_bytes(pts, o);
    ReadReport report;
    const PointSet laz = decode(laz_bytes, "p.laz", &report);
    EXPECT_LT(laz_bytes.size(), test::las_bytes(pts, LasWriteOptions{c.minor, c.format}).size());
    ASSERT_EQ(laz.size(), las.size());
    EXPECT_EQ(laz.positions.size(), las.positions.size());
    for (std::size_t i = 0; i < las.size(); ++i) ASSERT_TRUE(laz.positions[i] == las.positions[i]) << i;
    EXPECT_EQ(laz.scalars[0].values, las.scalars[0].values);
    ASSERT_EQ(laz.colors.size(), las.colors.size());
    for (std::size_t i = 0; i < las.colors.size(); ++i) ASSERT_TRUE(laz.colors[i] == las.colors[i]) << i;
    EXPECT_EQ(report.format, "laz 1." + std::to_string(c.minor) + " (point format " + std::to_string(c.format) + ")");
  }
}

TEST(Las, GeoreferencedPointsAreMovedByAnOriginAndKeepTheirResolution) {
  // UTM-like coordinates at millimetres: float cannot hold 4,100,000.123 to the millimetre, so the
  // reader subtracts the header box's centre (whole units) and says so.
  const double utm[3] = {512345.0, 4101234.0, 250.0};
  const std::vector<LasPoint> pts = test::random_las_points(500, 5, utm, 100.0);
  LasWriteOptions o;
  o.offset[0] = 500000, o.offset[1] = 4100000, o.offset[2] = 0;
  for (const bool laz : {false, true}) {
    o.compress = laz;
    ReadReport report;
    const PointSet got = decode(test::las_bytes(pts, o), "utm.las", &report);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const LasPoint& p : pts) {
      const double w[3] = {p.x, p.y, p.z};
      for (int a = 0; a < 3; ++a) {
        const double s = double(std::llround((w[a] - o.offset[a]) / o.scale[a])) * o.scale[a] + o.offset[a];
        lo[a] = std::min(lo[a], s), hi[a] = std::max(hi[a], s);
      }
    }
    const double origin[3] = {std::round(0.5 * (lo[0] + hi[0])), std::round(0.5 * (lo[1] + hi[1])), std::round(0.5 * (lo[2] + hi[2]))};
    expect_points(got, pts, o, origin);
    ASSERT_EQ(got.comments.size(), 1u);
    EXPECT_EQ(got.comments[0].rfind("origin ", 0), 0u) << got.comments[0];
    // Millimetres survive: every position is within a quarter millimetre of the file's value.
    for (std::size_t i = 0; i < pts.size(); ++i)
      ASSERT_NEAR(double(got.positions[i].y) + origin[1], pts[i].y, 0.00075) << i;
    bool found = false;
    for (const auto& kv : report.header) found |= kv.first == "origin" && kv.second != "0 0 0";
    EXPECT_TRUE(found);
  }
}

TEST(Las, EightBitColoursAreNotScaled) {
  std::vector<LasPoint> pts = test::random_las_points(50, 9, kCentre, 1.0);
  for (LasPoint& p : pts) p.r &= 0xff, p.g &= 0xff, p.b &= 0xff;
  LasWriteOptions o;
  o.format = 2;
  ReadReport report;
  const PointSet got = decode(test::las_bytes(pts, o), "c.las", &report);
  for (std::size_t i = 0; i < pts.size(); ++i)
    ASSERT_TRUE(got.colors[i] == (Rgb8{std::uint8_t(pts[i].r), std::uint8_t(pts[i].g), std::uint8_t(pts[i].b)})) << i;
  EXPECT_EQ(report.warnings.size(), 1u);
}

TEST(Las, FileAndMemoryReadersAgree) {
  // read_las streams the file in blocks (several here: 4 MiB of 34-byte records is ~123k points).
  const std::vector<LasPoint> pts = test::random_las_points(150000, 21, kCentre, 200.0);
  test::TempDir dir;
  for (const bool laz : {false, true}) {
    LasWriteOptions o;
    o.compress = laz;
    const std::string bytes = test::las_bytes(pts, o);
    const std::string path = dir.write(laz ? "big.laz" : "big.las", bytes);
    const PointSet from_file = read_las(path), from_memory = decode(bytes, path);
    ASSERT_EQ(from_file.size(), pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) ASSERT_TRUE(from_file.positions[i] == from_memory.positions[i]) << i;
    EXPECT_EQ(from_file.scalars[0].values, from_memory.scalars[0].values);
  }
}

TEST(Las, StreamedBlocksAreTheWholeRead) {
  // Colours over 16 bits, and 8-bit colours (the whole file must be scanned to say so); LAS and
  // LAZ; blocks smaller than a LAZ chunk and larger.
  test::TempDir dir;
  std::vector<LasPoint> pts = test::random_las_points(3000, 13, kCentre, 40.0);
  std::vector<LasPoint> dark = pts;
  for (LasPoint& p : dark) p.r &= 0xff, p.g &= 0xff, p.b &= 0xff;
  for (const bool laz : {false, true})
    for (const bool eight : {false, true})
      for (const std::size_t block : {std::size_t{700}, std::size_t{5000}}) {
        SCOPED_TRACE(std::string(laz ? "laz" : "las") + (eight ? " 8-bit" : " 16-bit") + " blocks of " + std::to_string(block));
        LasWriteOptions o;
        o.compress = laz, o.chunk_size = 1000;
        const std::string path = dir.write(laz ? "s.laz" : "s.las", test::las_bytes(eight ? dark : pts, o));
        ReadReport whole_report, report;
        const PointSet whole = read_las(path, {}, &whole_report);
        EXPECT_EQ(streamed_point_count(path), std::optional<std::size_t>(3000));
        PointSet got;
        std::size_t blocks = 0;
        stream_point_set(path, {}, &report, block, [&](PointSet& b) {
          ++blocks;
          EXPECT_LE(b.size(), block);
          got.positions.insert(got.positions.end(), b.positions.begin(), b.positions.end());
          got.colors.insert(got.colors.end(), b.colors.begin(), b.colors.end());
        });
        EXPECT_EQ(blocks, (3000 + block - 1) / block);
        EXPECT_TRUE(got.positions == whole.positions);
        EXPECT_TRUE(got.colors == whole.colors);
        EXPECT_EQ(report.warnings, whole_report.warnings);
        EXPECT_EQ(report.format, whole_report.format);
      }
}

// ---------------------------------------------------------------------------------------------
// Malformed files: each broken field gives its own code, with the file and a byte offset.

std::string small_file(int format = 3, bool laz = false, int minor = 2) {
  LasWriteOptions o;
  o.format = format, o.compress = laz, o.minor = minor, o.chunk_size = 20;
  return test::las_bytes(test::random_las_points(50, 1, kCentre, 5.0), o);
}
template <class T>
std::string patched(std::string b, std::size_t at, T v) {
  if (at + sizeof v > b.size()) throw std::logic_error("patch past the end");
  std::memcpy(&b[at], &v, sizeof v);
  return b;
}

TEST(LasMalformed, HeaderFields) {
  const std::string good = small_file();
  EXPECT_EQ(error_code(""), "las.header.magic");
  EXPECT_EQ(error_code("LASX" + good.substr(4)), "las.header.magic");
  EXPECT_EQ(error_code(good.substr(0, 100)), "las.header.truncated");
  EXPECT_EQ(error_code(patched(good, 24, std::uint8_t(2))), "las.header.version");
  EXPECT_EQ(error_code(patched(good, 25, std::uint8_t(5))), "las.header.version");
  EXPECT_EQ(error_code(patched(good, 94, std::uint16_t(200))), "las.header.size");
  EXPECT_EQ(error_code(patched(good, 96, std::uint32_t(100))), "las.header.point_offset");
  EXPECT_EQ(error_code(patched(good, 96, std::uint32_t(1u << 30))), "las.header.point_offset");
  EXPECT_EQ(error_code(patched(good, 104, std::uint8_t(11))), "las.header.format");
  EXPECT_EQ(error_code(patched(good, 104, std::uint8_t(0x43))), "las.header.format");
  EXPECT_EQ(error_code(patched(good, 105, std::uint16_t(30))), "las.header.record_length");
  EXPECT_EQ(error_code(patched(good, 139, 0.0)), "las.header.scale");
  EXPECT_EQ(error_code(patched(good, 131, double(NAN))), "las.header.scale");
  EXPECT_EQ(error_code(patched(good, 171, double(INFINITY))), "las.header.offset");
  EXPECT_EQ(error_code(patched(good, 107, std::uint32_t(0))), "las.empty");
  // A 1.4 header's 64-bit count decides; a 1.3 header is 235 bytes.
  EXPECT_EQ(error_code(patched(small_file(6, false, 4), 247, std::uint64_t(1) << 40)), "las.body.truncated");
  EXPECT_EQ(error_code(patched(small_file(3, false, 3), 94, std::uint16_t(227))), "las.header.size");
}

TEST(LasMalformed, CountsThatDisagreeWithTheFile) {
  const std::string good = small_file();
  EXPECT_EQ(error_code(good.substr(0, good.size() - 1)), "las.body.truncated");
  EXPECT_EQ(error_code(patched(good, 107, std::uint32_t(0xFFFFFFFF))), "las.body.truncated");
  EXPECT_EQ(error_code(patched(good, 100, std::uint32_t(1))), "las.vlr");  // a VLR where the points are
  std::string evlr = patched(small_file(6, false, 4), 243, std::uint32_t(2));
  EXPECT_EQ(error_code(patched(evlr, 235, std::uint64_t(evlr.size() - 10))), "las.evlr");
  EXPECT_EQ(error_code(patched(evlr, 235, std::uint64_t(10))), "las.evlr");
}

TEST(LasMalformed, LazStructures) {
  const std::string good = small_file(3, true);
  const std::size_t vlr = 227, data = vlr + 54, points = data + 34 + 6 * 3;
  std::uint64_t table;
  std::memcpy(&table, &good[points], 8);
  EXPECT_EQ(error_code(patched(good, 100, std::uint32_t(0)), "bad.laz"), "laz.vlr");  // VLR not counted
  EXPECT_EQ(error_code(patched(good, data, std::uint16_t(1)), "bad.laz"), "laz.unsupported");  // pointwise compressor
  EXPECT_EQ(error_code(patched(good, data + 34 + 4, std::uint16_t(1)), "bad.laz"), "laz.unsupported");  // item version 1
  EXPECT_EQ(error_code(patched(good, data + 12, std::uint32_t(0)), "bad.laz"), "laz.vlr");  // chunk size 0
  const std::string format4 = patched(good, 104, std::uint8_t(0x84));
  EXPECT_EQ(error_code(patched(format4, 105, std::uint16_t(57)), "bad.laz"), "laz.unsupported");  // waveforms
  EXPECT_EQ(error_code(patched(good, points, std::int64_t(-1)), "bad.laz"), "laz.chunk_table");
  EXPECT_EQ(error_code(patched(good, points, std::int64_t(5)), "bad.laz"), "laz.chunk_table");
  EXPECT_EQ(error_code(patched(good, points, std::int64_t(good.size())), "bad.laz"), "laz.chunk_table");
  EXPECT_EQ(error_code(patched(good, table, std::uint32_t(1)), "bad.laz"), "laz.chunk_table");  // version
  EXPECT_EQ(error_code(patched(good, table + 4, std::uint32_t(0xFFFFFFF)), "bad.laz"), "laz.chunk_table");
  EXPECT_EQ(error_code(patched(good, table + 4, std::uint32_t(2)), "bad.laz"), "laz.chunk_table");  // 50 points / 20 = 3
  EXPECT_EQ(error_code(patched(good, 107, std::uint32_t(70)), "bad.laz"), "laz.chunk_table");
  EXPECT_EQ(error_code(good.substr(0, good.size() - 3), "bad.laz"), "laz.chunk_table");
}

TEST(LasMalformed, LayeredChunkSizes) {
  // A 1.4 chunk counts its layers' bytes; counts beyond the chunk are refused before laz-perf
  // allocates them.
  const std::string good = small_file(7, true, 4);
  const std::size_t points = 375 + 54 + 34 + 6 * 2;
  const std::size_t layers = points + 8 + 36 + 4;  // first raw point (36 bytes), point count
  EXPECT_EQ(error_code(patched(good, layers, std::uint32_t(0x7FFFFFFF)), "bad.laz"), "laz.chunk");
  EXPECT_EQ(error_code(patched(good, layers - 4, std::uint32_t(17)), "bad.laz"), "laz.chunk");  // it holds 20
}

TEST(LasMalformed, TruncationsAndBitFlipsNeverCrash) {
  // Prefixes, and bytes flipped, of small LAS and LAZ files: read or refused with an InputError,
  // never a crash or another exception (ASan/UBSan in the sanitizer pass). Every byte of the
  // header, VLRs and chunk table offset (but the two free-text fields, system identifier and
  // generating software, bytes 26-89, which nothing reads), flipped in its lowest bit or whole
  // (alternately); every 7th (cuts) or 5th (flips) byte of the points, as each LAZ decode builds
  // laz-perf's models afresh (~1-3 ms a chunk; ~25 under ASan: the test took 193 s there with
  // both flips of every byte).
  for (const auto& [format, laz, minor] : {std::tuple{3, false, 2}, {3, true, 2}, {1, true, 2}, {7, true, 4}, {8, true, 4}, {6, false, 4}}) {
    LasWriteOptions o;
    o.format = format, o.compress = laz, o.minor = minor, o.chunk_size = 16;
    const std::string good = test::las_bytes(test::random_las_points(30, 1, kCentre, 5.0), o);
    std::uint32_t point_offset;
    std::memcpy(&point_offset, &good[96], 4);
    const std::size_t head = point_offset + 8;
    const auto text = [](std::size_t i) { return i >= 26 && i < 90; };
    // Streamed (stream_point_set, in blocks of 7), a cut file is read or refused as a whole read
    // is: the same error code, else the same points.
    for (std::size_t n = 0; n < good.size(); n += n < head ? 1 : 7) {
      if (text(n)) continue;
      const std::string cut = good.substr(0, n);
      std::string whole_code = "accepted", stream_code = "accepted";
      std::vector<Vec3f> whole, streamed;
      try {
        whole = decode(cut, "cut.las").positions;
      } catch (const InputError& e) {
        whole_code = e.code();
      }
      try {
        const ByteView v(reinterpret_cast<const std::uint8_t*>(cut.data()), cut.size());
        stream_point_set(v, "cut.las", {}, nullptr, 7, [&](PointSet& b) { streamed.insert(streamed.end(), b.positions.begin(), b.positions.end()); });
      } catch (const InputError& e) {
        stream_code = e.code();
      }
      ASSERT_EQ(stream_code, whole_code) << "cut at " << n;
      if (whole_code == "accepted") {
        ASSERT_TRUE(streamed == whole) << "cut at " << n;
      }
    }
    for (std::size_t i = 0; i < good.size(); i += i < head ? 1 : 5) {
      if (text(i)) continue;
      std::string b = good;
      b[i] = static_cast<char>(b[i] ^ (i < head && i % 2 == 0 ? 0x01 : 0xFF));
      try {
        decode(b, "flip.laz");
      } catch (const InputError&) {
      }
    }
  }
}

}  // namespace
}  // namespace qf
