// LAS 1.0–1.4 and LAZ reader (ASPRS LAS specification R15; LAZ as written by LASzip and laz-perf).
// The header, VLRs/EVLRs, chunk table bounds and point records are parsed here; laz-perf 3.4.0
// (third_party/laz-perf) only decodes the compressed chunks. The file is streamed: a block of
// records (LAS) or one chunk (LAZ) is read at a time, never the whole file.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <sstream>

#include "core/error.h"
#include "core/file_io.h"
#include "core/memory.h"
#include "io/model_io.h"
#include "lazperf/lazperf.hpp"

namespace qf {
namespace {

// ---------------------------------------------------------------------------------------------
// Where the bytes come from: a file read piecewise (pread), or bytes already in memory.

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual std::uint64_t size() const = 0;
  // Copies [offset, offset + n) to out; the caller has checked that the range lies in the file.
  virtual void read(std::uint64_t offset, std::size_t n, std::uint8_t* out) const = 0;
};

class MemorySource final : public ByteSource {
 public:
  explicit MemorySource(ByteView bytes) : bytes_(bytes) {}
  std::uint64_t size() const override { return bytes_.size(); }
  void read(std::uint64_t offset, std::size_t n, std::uint8_t* out) const override {
    if (n) std::memcpy(out, bytes_.data() + offset, n);
  }

 private:
  ByteView bytes_;
};

class FileSource final : public ByteSource {
 public:
  FileSource(int fd, std::uint64_t size, const std::string& path) : fd_(fd), size_(size), path_(path) {}
  ~FileSource() override { ::close(fd_); }
  std::uint64_t size() const override { return size_; }
  void read(std::uint64_t offset, std::size_t n, std::uint8_t* out) const override {
    while (n > 0) {
      const ssize_t got = ::pread(fd_, out, n, static_cast<off_t>(offset));
      if (got < 0 && errno == EINTR) continue;
      // A file that shrinks while we read it (or an I/O error) ends the read here.
      if (got <= 0)
        throw InputError("file.unreadable", path_, at_byte(offset),
                         got == 0 ? "the file ended early (changed while being read?)" : std::string("read error: ") + std::strerror(errno));
      out += got, offset += static_cast<std::uint64_t>(got), n -= static_cast<std::size_t>(got);
    }
  }

 private:
  int fd_;
  std::uint64_t size_;
  const std::string& path_;
};

std::uint16_t le16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::uint32_t le32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) | (std::uint32_t(p[3]) << 24);
}
std::uint64_t le64(const std::uint8_t* p) { return std::uint64_t(le32(p)) | (std::uint64_t(le32(p + 4)) << 32); }
std::int32_t le_i32(const std::uint8_t* p) { return static_cast<std::int32_t>(le32(p)); }
double le_double(const std::uint8_t* p) {
  const std::uint64_t u = le64(p);
  double d;
  std::memcpy(&d, &u, 8);
  return d;
}
// A fixed-width text field (system identifier, VLR user id) up to its first NUL.
std::string fixed_text(const std::uint8_t* p, std::size_t n) {
  std::size_t len = 0;
  while (len < n && p[len] != 0) ++len;
  std::string s(reinterpret_cast<const char*>(p), len);
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// Record sizes of point data formats 0..10 (LAS 1.4 R15, tables 7–32), without extra bytes.
constexpr std::uint16_t kRecordSize[11] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
// Where the 16-bit RGB triple sits in each format's record (0: the format has none).
constexpr std::uint16_t kRgbOffset[11] = {0, 0, 20, 28, 0, 28, 0, 30, 30, 0, 30};

// The smallest public header block of each minor version (1.0–1.2, 1.3, 1.4).
std::uint16_t min_header_size(int minor) { return minor <= 2 ? 227 : minor == 3 ? 235 : 375; }

struct LasHeader {
  int major = 0, minor = 0;
  std::uint16_t header_size = 0;
  std::uint32_t point_offset = 0, vlr_count = 0;
  int format = 0;
  bool compressed = false;
  std::uint16_t record_length = 0;
  std::uint64_t count = 0;
  double scale[3] = {}, offset[3] = {}, max[3] = {}, min[3] = {};
  std::uint64_t evlr_offset = 0;
  std::uint32_t evlr_count = 0;
  std::string system_id, software;
  std::uint16_t extra_bytes() const { return static_cast<std::uint16_t>(record_length - kRecordSize[format]); }
};

// The LASzip VLR (user "laszip encoded", record 22204), LASzip's laszip.hpp layout.
struct LaszipVlr {
  bool found = false;
  std::uint64_t where = 0;  // file offset of its data
  std::uint16_t compressor = 0, coder = 0;
  int version_major = 0, version_minor = 0;
  std::uint32_t chunk_size = 0;
  struct Item {
    std::uint16_t type, size, version;
  };
  std::vector<Item> items;
};

class LasReader {
 public:
  LasReader(const ByteSource& src, const std::string& path, ReadReport* report)
      : src_(src), path_(path), report_(report) {}
  PointSet read();
  // The header's point count (the header alone read and checked).
  std::uint64_t count() {
    read_header();
    return h_.count;
  }
  // The points a block at a time (model_io.h stream_point_set).
  void stream(std::size_t block_points, const std::function<void(PointSet&)>& block);

 private:
  [[noreturn]] void fail(const char* code, std::uint64_t offset, const std::string& detail) const {
    throw InputError(code, path_, at_byte(offset), detail);
  }
  void read_header();
  void read_meta();
  void read_points();
  void flush_block();
  void read_vlrs();
  void read_evlrs();
  void take_laszip_vlr(std::uint64_t data, std::uint64_t length);
  void choose_origin();
  void prepare_output();
  void add_record(const std::uint8_t* rec);
  void read_las_points();
  void read_laz_points();
  std::vector<std::uint64_t> read_chunk_table(std::uint64_t first_chunk, std::uint64_t& table_offset,
                                              std::vector<std::uint64_t>& counts);
  void decode_chunk(std::size_t index, std::uint64_t offset, std::uint64_t bytes, std::uint64_t count);
  void check_layers(const std::vector<std::uint8_t>& chunk, std::size_t index, std::uint64_t offset, std::uint64_t count) const;
  void finish_colors();
  void report_facts() const;

  const ByteSource& src_;
  const std::string& path_;
  ReadReport* report_;
  LasHeader h_;
  LaszipVlr laz_;
  std::vector<std::string> vlr_names_;
  double origin_[3] = {0, 0, 0};
  PointSet out_;
  std::vector<std::array<std::uint16_t, 3>> rgb16_;  // until every point is read: 8 or 16 bits?
  std::uint16_t rgb_max_ = 0;
  std::vector<float>* classes_ = nullptr;
  // Streaming: blocks of block_points_ handed to block_; colours shifted by shift_ (known before
  // the points are read: scanning_ is the pass that finds it, done_ when a value past 255 ends it).
  const std::function<void(PointSet&)>* block_ = nullptr;
  std::size_t block_points_ = 0;
  int shift_ = 0;
  bool scanning_ = false, done_ = false;
};

// ---------------------------------------------------------------------------------------------
// Header, VLRs, EVLRs.

void LasReader::read_header() {
  // 1. Magic and the fixed part every version shares (1.0: 227 bytes).
  const std::uint64_t size = src_.size();
  std::uint8_t b[375] = {};
  src_.read(0, static_cast<std::size_t>(std::min<std::uint64_t>(size, sizeof b)), b);
  if (size < 4 || std::memcmp(b, "LASF", 4) != 0) fail("las.header.magic", 0, "expected the LAS signature 'LASF'");
  if (size < 227) fail("las.header.truncated", size, "the file ends inside the 227-byte LAS header");
  h_.major = b[24], h_.minor = b[25];
  if (h_.major != 1 || h_.minor > 4)
    fail("las.header.version", 24, "LAS version " + std::to_string(h_.major) + "." + std::to_string(h_.minor) + ", expected 1.0 to 1.4");
  h_.system_id = fixed_text(b + 26, 32);
  h_.software = fixed_text(b + 58, 32);
  h_.header_size = le16(b + 94);
  h_.point_offset = le32(b + 96);
  h_.vlr_count = le32(b + 100);
  if (h_.header_size < min_header_size(h_.minor))
    fail("las.header.size", 94, "header size " + std::to_string(h_.header_size) + ", LAS 1." + std::to_string(h_.minor) +
                                    " needs at least " + std::to_string(min_header_size(h_.minor)));
  if (h_.header_size > size) fail("las.header.truncated", size, "the file ends inside its " + std::to_string(h_.header_size) + "-byte header");
  if (h_.point_offset < h_.header_size || h_.point_offset > size)
    fail("las.header.point_offset", 96, "point data offset " + std::to_string(h_.point_offset) + ", expected between the header's end (" +
                                            std::to_string(h_.header_size) + ") and the file's size (" + std::to_string(size) + ")");

  // 2. Point format: bit 7 marks LAZ (LASzip); bit 6 alone or with it, older compressors.
  const int fmt = b[104];
  if (fmt & 0x40) fail("las.header.format", 104, "point format byte " + std::to_string(fmt) + ": an old or unknown compression (bit 6)");
  h_.compressed = (fmt & 0x80) != 0;
  h_.format = fmt & 0x3f;
  if (h_.format > 10) fail("las.header.format", 104, "point data format " + std::to_string(h_.format) + ", expected 0 to 10");
  h_.record_length = le16(b + 105);
  if (h_.record_length < kRecordSize[h_.format])
    fail("las.header.record_length", 105, "point record length " + std::to_string(h_.record_length) + ", format " +
                                              std::to_string(h_.format) + " needs at least " + std::to_string(kRecordSize[h_.format]));

  // 3. Scale and offset: X = X_record * scale + offset.
  for (int a = 0; a < 3; ++a) {
    h_.scale[a] = le_double(b + 131 + 8 * a);
    h_.offset[a] = le_double(b + 155 + 8 * a);
    h_.max[a] = le_double(b + 179 + 16 * a);
    h_.min[a] = le_double(b + 187 + 16 * a);
    if (!std::isfinite(h_.scale[a]) || h_.scale[a] == 0)
      fail("las.header.scale", 131 + 8 * a, "scale factor " + std::to_string(h_.scale[a]) + ", expected a finite non-zero number");
    if (!std::isfinite(h_.offset[a]) || std::abs(h_.offset[a]) > 1e300)
      fail("las.header.offset", 155 + 8 * a, "offset " + std::to_string(h_.offset[a]) + ", expected a finite number");
  }

  // 4. Point count: 1.4 has a 64-bit count (the 32-bit legacy one is 0 for formats 6–10).
  h_.count = le32(b + 107);
  if (h_.minor >= 4) {
    h_.evlr_offset = le64(b + 235);
    h_.evlr_count = le32(b + 243);
    const std::uint64_t count64 = le64(b + 247);
    if (count64 != 0) h_.count = count64;
  }
  if (h_.count == 0) fail("las.empty", 107, "the header counts no points");
}

void LasReader::read_vlrs() {
  // VLRs follow the header and end where the points begin (R15 §2.5).
  std::uint64_t at = h_.header_size;
  for (std::uint32_t i = 0; i < h_.vlr_count; ++i) {
    if (at + 54 > h_.point_offset)
      fail("las.vlr", at, "VLR " + std::to_string(i) + " of " + std::to_string(h_.vlr_count) +
                              ": its 54-byte header does not fit before the point data at byte " + std::to_string(h_.point_offset));
    std::uint8_t v[54];
    src_.read(at, 54, v);
    const std::string user = fixed_text(v + 2, 16);
    const std::uint16_t record = le16(v + 18), length = le16(v + 20);
    if (at + 54 + length > h_.point_offset)
      fail("las.vlr", at + 20, "VLR " + std::to_string(i) + " ('" + user + "' " + std::to_string(record) + ") has " +
                                   std::to_string(length) + " bytes, past the point data at byte " + std::to_string(h_.point_offset));
    vlr_names_.push_back(user + " " + std::to_string(record));
    if (user == "laszip encoded" && record == 22204) take_laszip_vlr(at + 54, length);
    at += 54 + length;
  }
}

void LasReader::read_evlrs() {
  // EVLRs (1.4) sit after the point data; each has a 60-byte header with a 64-bit length.
  if (h_.evlr_count == 0) return;
  const std::uint64_t size = src_.size();
  std::uint64_t at = h_.evlr_offset;
  if (at < h_.point_offset) fail("las.evlr", 235, "EVLR offset " + std::to_string(at) + " lies before the point data");
  for (std::uint32_t i = 0; i < h_.evlr_count; ++i) {
    if (at > size || size - at < 60)
      fail("las.evlr", std::min(at, size), "EVLR " + std::to_string(i) + " of " + std::to_string(h_.evlr_count) + ": its 60-byte header is past the end of the file");
    std::uint8_t v[60];
    src_.read(at, 60, v);
    const std::string user = fixed_text(v + 2, 16);
    const std::uint16_t record = le16(v + 18);
    const std::uint64_t length = le64(v + 20);
    if (length > size - at - 60)
      fail("las.evlr", at + 20, "EVLR " + std::to_string(i) + " ('" + user + "' " + std::to_string(record) + ") has " +
                                    std::to_string(length) + " bytes, past the end of the file");
    vlr_names_.push_back(user + " " + std::to_string(record) + " (extended)");
    if (user == "laszip encoded" && record == 22204) take_laszip_vlr(at + 60, length);
    at += 60 + length;
  }
}

void LasReader::take_laszip_vlr(std::uint64_t data, std::uint64_t length) {
  if (laz_.found) fail("laz.vlr", data, "a second LASzip VLR");
  if (length < 34 || length > 65535) fail("laz.vlr", data, "LASzip VLR of " + std::to_string(length) + " bytes, expected 34 + 6 per item");
  std::vector<std::uint8_t> v(static_cast<std::size_t>(length));
  src_.read(data, v.size(), v.data());
  laz_.found = true;
  laz_.where = data;
  laz_.compressor = le16(&v[0]);
  laz_.coder = le16(&v[2]);
  laz_.version_major = v[4], laz_.version_minor = v[5];
  laz_.chunk_size = le32(&v[12]);
  const std::uint16_t items = le16(&v[32]);
  if (34 + 6 * std::size_t(items) > v.size())
    fail("laz.vlr", data + 32, std::to_string(items) + " items do not fit in the LASzip VLR's " + std::to_string(length) + " bytes");
  for (std::size_t i = 0; i < items; ++i) laz_.items.push_back({le16(&v[34 + 6 * i]), le16(&v[36 + 6 * i]), le16(&v[38 + 6 * i])});
}

// ---------------------------------------------------------------------------------------------
// Points: positions, colours, classification.

void LasReader::choose_origin() {
  // Positions are floats (core/types.h): 24 bits hold a coordinate to the file's resolution
  // (its scale) only while |coordinate| <= 2^23 x scale. Georeferenced files (UTM: 10^5–10^7 m
  // at millimetres) do not fit, so their points are moved by an origin: the centre of the
  // header's bounding box, rounded to whole units, recorded in the comments and the report.
  bool fits = true;
  double centre[3];
  for (int a = 0; a < 3; ++a) {
    const double lo = h_.min[a], hi = h_.max[a];
    const bool box_ok = std::isfinite(lo) && std::isfinite(hi) && lo <= hi && std::abs(lo) < 1e300 && std::abs(hi) < 1e300;
    centre[a] = box_ok ? std::round(0.5 * (lo + hi)) : std::round(h_.offset[a]);
    const double reach = box_ok ? std::max(std::abs(lo), std::abs(hi)) : std::abs(h_.offset[a]);
    if (reach > 8388608.0 * std::abs(h_.scale[a])) fits = false;
  }
  if (!fits) std::copy(centre, centre + 3, origin_);
  // Every record must give a finite float: the largest integer times the scale, plus what is
  // left of the offset, stays within float's range.
  for (int a = 0; a < 3; ++a)
    if (!(std::abs(h_.scale[a]) * 2147483648.0 + std::abs(h_.offset[a] - origin_[a]) < 3.0e38))
      fail("las.header.scale", 131 + 8 * a, "scale " + std::to_string(h_.scale[a]) + " and offset " + std::to_string(h_.offset[a]) +
                                                " put coordinates beyond the range of a float");
  if (fits) return;
  std::ostringstream c;
  c.precision(15);
  c << "origin " << centre[0] << " " << centre[1] << " " << centre[2]
    << " (LAS coordinates = position + origin; the points were moved to keep float precision)";
  out_.comments.push_back(c.str());
}

void LasReader::prepare_output() {
  // Reserve what the header counts only when the file can hold it (LAS: checked against the
  // file's size before; LAZ: at most what its chunks can hold at the densest rate we accept);
  // streaming, a block.
  const std::size_t n = block_ ? std::min<std::size_t>(block_points_, static_cast<std::size_t>(h_.count)) : static_cast<std::size_t>(h_.count);
  if (scanning_) return;
  reserve_huge(out_.positions, n);
  if (kRgbOffset[h_.format]) block_ ? reserve_huge(out_.colors, n) : reserve_huge(rgb16_, n);
  out_.scalars.push_back({"classification", {}});
  reserve_huge(out_.scalars.back().values, n);
}

void LasReader::add_record(const std::uint8_t* rec) {
  if (scanning_) {  // the colours' widest value only; a value past 255 settles it
    const std::uint16_t o = kRgbOffset[h_.format];
    rgb_max_ = std::max({rgb_max_, le16(rec + o), le16(rec + o + 2), le16(rec + o + 4)});
    done_ = rgb_max_ > 255;
    return;
  }
  Vec3f p;
  for (int a = 0; a < 3; ++a)
    p[a] = static_cast<float>(double(le_i32(rec + 4 * a)) * h_.scale[a] + (h_.offset[a] - origin_[a]));
  out_.positions.push_back(p);
  // Classification: the low 5 bits of byte 15 in formats 0–5, the whole byte 16 in 6–10.
  out_.scalars[0].values.push_back(static_cast<float>(h_.format < 6 ? (rec[15] & 31) : rec[16]));
  if (const std::uint16_t o = kRgbOffset[h_.format]) {
    const std::array<std::uint16_t, 3> c{le16(rec + o), le16(rec + o + 2), le16(rec + o + 4)};
    if (block_) {
      out_.colors.push_back({static_cast<std::uint8_t>(c[0] >> shift_), static_cast<std::uint8_t>(c[1] >> shift_),
                             static_cast<std::uint8_t>(c[2] >> shift_)});
    } else {
      rgb_max_ = std::max({rgb_max_, c[0], c[1], c[2]});
      rgb16_.push_back(c);
    }
  }
  if (block_ && out_.positions.size() >= block_points_) flush_block();
}

void LasReader::flush_block() {
  if (out_.positions.empty()) return;
  (*block_)(out_);
  out_.positions.clear(), out_.colors.clear();
  out_.scalars.resize(1);
  out_.scalars[0].name = "classification";
  out_.scalars[0].values.clear();
}

void LasReader::finish_colors() {
  // LAS stores 16-bit colour, but many writers store 8-bit values unscaled: when no channel
  // exceeds 255 the values are taken as 8-bit, else the high byte is kept.
  if (rgb16_.empty()) return;
  const int shift = rgb_max_ > 255 ? 8 : 0;
  out_.colors.resize(rgb16_.size());
  for (std::size_t i = 0; i < rgb16_.size(); ++i)
    out_.colors[i] = {static_cast<std::uint8_t>(rgb16_[i][0] >> shift), static_cast<std::uint8_t>(rgb16_[i][1] >> shift),
                      static_cast<std::uint8_t>(rgb16_[i][2] >> shift)};
  std::vector<std::array<std::uint16_t, 3>>().swap(rgb16_);
  if (report_ && shift == 0) report_->warnings.push_back("colour values all <= 255: read as 8-bit, not scaled from 16-bit");
}

void LasReader::read_las_points() {
  // Records lie back to back from the point offset; the count must fit in the file.
  const std::uint64_t size = src_.size(), rl = h_.record_length;
  if (h_.count > (size - h_.point_offset) / rl)
    fail("las.body.truncated", h_.point_offset,
         std::to_string(h_.count) + " points of " + std::to_string(rl) + " bytes need " + std::to_string(h_.count * rl) +
             " bytes from byte " + std::to_string(h_.point_offset) + "; the file has " + std::to_string(size - h_.point_offset));
  prepare_output();
  // Blocks of about 4 MiB: large enough that reads are cheap, small enough to stay out of RSS.
  const std::uint64_t per_block = std::max<std::uint64_t>(1, (std::uint64_t(4) << 20) / rl);
  std::vector<std::uint8_t> block(static_cast<std::size_t>(std::min(per_block, h_.count) * rl));
  for (std::uint64_t first = 0; first < h_.count && !done_; first += per_block) {
    const std::uint64_t n = std::min(per_block, h_.count - first);
    src_.read(h_.point_offset + first * rl, static_cast<std::size_t>(n * rl), block.data());
    for (std::uint64_t i = 0; i < n && !done_; ++i) add_record(block.data() + i * rl);
  }
}

// ---------------------------------------------------------------------------------------------
// LAZ: the LASzip VLR, the chunk table, and each chunk decoded by laz-perf.

// What laz-perf 3.4.0 decodes: LASzip's "pointwise chunked" items (version 2) for formats 0–3,
// "layered chunked" items (version 3) for 6–8. Item types from LASzip's laszip.hpp.
enum : std::uint16_t { kByte = 0, kPoint10 = 6, kGpsTime11 = 7, kRgb12 = 8, kPoint14 = 10, kRgb14 = 11, kRgbNir14 = 12, kByte14 = 14 };

std::vector<LaszipVlr::Item> expected_items(int format, std::uint16_t extra) {
  std::vector<LaszipVlr::Item> v;
  if (format <= 3) {
    v.push_back({kPoint10, 20, 2});
    if (format == 1 || format == 3) v.push_back({kGpsTime11, 8, 2});
    if (format == 2 || format == 3) v.push_back({kRgb12, 6, 2});
    if (extra) v.push_back({kByte, extra, 2});
  } else {
    v.push_back({kPoint14, 30, 3});
    if (format == 7) v.push_back({kRgb14, 6, 3});
    if (format == 8) v.push_back({kRgbNir14, 8, 3});
    if (extra) v.push_back({kByte14, extra, 3});
  }
  return v;
}

// The compressed bytes of one chunk, handed to laz-perf on request. Reads past the chunk's end
// give zeros and are remembered: the chunk is then refused once the point being decoded is done.
struct ChunkInput {
  const std::uint8_t* data;
  std::size_t size, pos = 0;
  bool overrun = false;
  void take(unsigned char* out, std::size_t n) {
    const std::size_t have = pos < size ? std::min(n, size - pos) : 0;
    if (have) std::memcpy(out, data + pos, have);
    if (have < n) std::memset(out + have, 0, n - have), overrun = true;
    pos += n;
  }
};

// Arithmetic coding can store a run of identical points in a fraction of a byte each, so a chunk's
// point count cannot be checked against its bytes exactly. Real files stay far below this bound
// (laz-perf packs 50,000 points differing only in their scan angle into ~9 KB: 5.5 points a
// byte), which keeps a small forged file from claiming billions of points.
constexpr std::uint64_t kMaxPointsPerChunkByte = 1024;

std::vector<std::uint64_t> LasReader::read_chunk_table(std::uint64_t first_chunk, std::uint64_t& table_offset,
                                                       std::vector<std::uint64_t>& counts) {
  // 1. The 8 bytes at the point offset locate the table (-1: never written, as by a writer that
  //    could not seek back; LASzip then scans the chunks, which we do not).
  const std::uint64_t size = src_.size();
  if (size - h_.point_offset < 8) fail("laz.chunk_table", h_.point_offset, "the file ends before the chunk table's offset");
  std::uint8_t b[8];
  src_.read(h_.point_offset, 8, b);
  const std::int64_t at = static_cast<std::int64_t>(le64(b));
  if (at == -1) fail("laz.chunk_table", h_.point_offset, "chunk table offset -1 (a LAZ file without its chunk table) is not supported");
  if (at < std::int64_t(first_chunk) || std::uint64_t(at) > size || size - std::uint64_t(at) < 8)
    fail("laz.chunk_table", h_.point_offset, "chunk table offset " + std::to_string(at) + ", expected between byte " +
                                                 std::to_string(first_chunk) + " and 8 bytes before the end (" + std::to_string(size) + ")");
  table_offset = static_cast<std::uint64_t>(at);
  src_.read(table_offset, 8, b);
  const std::uint32_t version = le32(b), chunks = le32(b + 4);
  if (version != 0) fail("laz.chunk_table", table_offset, "chunk table version " + std::to_string(version) + ", expected 0");
  // 2. Every chunk holds at least one byte before the table: bounds the table before allocating it.
  if (chunks == 0 || chunks > table_offset - first_chunk)
    fail("laz.chunk_table", table_offset + 4, std::to_string(chunks) + " chunks, expected 1 to " + std::to_string(table_offset - first_chunk) +
                                                  " (the bytes between the first chunk and the table)");
  const bool variable = laz_.chunk_size == 0xFFFFFFFFu;
  if (!variable && (h_.count + laz_.chunk_size - 1) / laz_.chunk_size != chunks)
    fail("laz.chunk_table", table_offset + 4, std::to_string(chunks) + " chunks, but " + std::to_string(h_.count) +
                                                  " points in chunks of " + std::to_string(laz_.chunk_size) + " make " +
                                                  std::to_string((h_.count + laz_.chunk_size - 1) / laz_.chunk_size));
  // 3. The table itself is arithmetic-coded (sizes, and counts for variable chunks).
  std::vector<std::uint8_t> coded(static_cast<std::size_t>(std::min<std::uint64_t>(size - table_offset - 8, 8 + 16 * std::uint64_t(chunks))));
  src_.read(table_offset + 8, coded.size(), coded.data());
  ChunkInput in{coded.data(), coded.size()};
  const std::vector<lazperf::chunk> table =
      lazperf::decompress_chunk_table([&in](unsigned char* out, std::size_t n) { in.take(out, n); }, chunks, variable);
  if (in.overrun) fail("laz.chunk_table", table_offset + 8, "the chunk table ends before its " + std::to_string(chunks) + " entries");
  // 4. Sizes and counts must add up to the bytes before the table and the header's count.
  std::vector<std::uint64_t> sizes;
  std::uint64_t bytes = 0, points = 0;
  for (std::size_t i = 0; i < table.size(); ++i) {
    const std::uint64_t n = variable ? table[i].count : std::min<std::uint64_t>(laz_.chunk_size, h_.count - points);
    bytes += table[i].offset;
    points += n;
    if (table[i].offset == 0 || bytes > table_offset - first_chunk || n == 0 || points > h_.count ||
        n > table[i].offset * kMaxPointsPerChunkByte)
      fail("laz.chunk_table", table_offset + 8, "chunk " + std::to_string(i) + " (" + std::to_string(n) + " points in " +
                                                    std::to_string(table[i].offset) + " bytes) does not fit between byte " +
                                                    std::to_string(first_chunk) + " and the table, or exceeds the header's " +
                                                    std::to_string(h_.count) + " points");
    sizes.push_back(table[i].offset);
    counts.push_back(n);
  }
  if (points != h_.count)
    fail("laz.chunk_table", table_offset + 8, "the chunks hold " + std::to_string(points) + " points, the header counts " + std::to_string(h_.count));
  return sizes;
}

void LasReader::check_layers(const std::vector<std::uint8_t>& chunk, std::size_t index, std::uint64_t offset, std::uint64_t count) const {
  // A layered (1.4) chunk: the first point raw, its point count, one byte count per layer, then
  // the layers. laz-perf allocates each layer's bytes as counted: they must lie in the chunk.
  const std::size_t layers = 9 + (h_.format == 7 ? 1 : h_.format == 8 ? 2 : 0) + h_.extra_bytes();
  const std::size_t head = h_.record_length + 4, table_end = head + 4 * layers;
  if (chunk.size() < table_end)
    fail("laz.chunk", offset, "chunk " + std::to_string(index) + " of " + std::to_string(chunk.size()) + " bytes is shorter than its layer table");
  if (le32(&chunk[h_.record_length]) != count)
    fail("laz.chunk", offset + h_.record_length, "chunk " + std::to_string(index) + " counts " + std::to_string(le32(&chunk[h_.record_length])) +
                                                     " points, its chunk table entry " + std::to_string(count));
  std::uint64_t sum = 0;
  for (std::size_t l = 0; l < layers; ++l) sum += le32(&chunk[head + 4 * l]);
  if (sum > chunk.size() - table_end)
    fail("laz.chunk", offset + head, "chunk " + std::to_string(index) + "'s layers count " + std::to_string(sum) + " bytes; the chunk has " +
                                         std::to_string(chunk.size() - table_end) + " after its layer table");
}

void LasReader::decode_chunk(std::size_t index, std::uint64_t offset, std::uint64_t bytes, std::uint64_t count) {
  std::vector<std::uint8_t> chunk(static_cast<std::size_t>(bytes));
  src_.read(offset, chunk.size(), chunk.data());
  if (h_.format >= 6) check_layers(chunk, index, offset, count);
  ChunkInput in{chunk.data(), chunk.size()};
  const lazperf::las_decompressor::ptr decoder = lazperf::build_las_decompressor(
      [&in](unsigned char* out, std::size_t n) { in.take(out, n); }, h_.format, h_.extra_bytes());
  std::vector<char> rec(h_.record_length);
  for (std::uint64_t i = 0; i < count && !done_; ++i) {
    decoder->decompress(rec.data());
    if (in.overrun)
      fail("laz.chunk", offset, "chunk " + std::to_string(index) + " (" + std::to_string(bytes) + " bytes) ends before point " +
                                    std::to_string(i) + " of its " + std::to_string(count));
    add_record(reinterpret_cast<const std::uint8_t*>(rec.data()));
  }
}

void LasReader::read_laz_points() {
  // 1. The LASzip VLR must describe exactly what laz-perf decodes for this format.
  if (!laz_.found) fail("laz.vlr", h_.header_size, "a compressed file without the LASzip VLR (user 'laszip encoded', record 22204)");
  if (h_.format == 4 || h_.format == 5 || h_.format == 9 || h_.format == 10)
    fail("laz.unsupported", 104, "compressed point format " + std::to_string(h_.format) + " (waveforms): laz-perf decodes formats 0-3 and 6-8");
  const std::uint16_t want_compressor = h_.format <= 3 ? 2 : 3;
  if (laz_.compressor != want_compressor || laz_.coder != 0)
    fail("laz.unsupported", laz_.where, "LASzip compressor " + std::to_string(laz_.compressor) + " coder " + std::to_string(laz_.coder) +
                                            ", expected compressor " + std::to_string(want_compressor) + " (chunked) for format " +
                                            std::to_string(h_.format) + " and coder 0");
  const std::vector<LaszipVlr::Item> want = expected_items(h_.format, h_.extra_bytes());
  bool same = want.size() == laz_.items.size();
  for (std::size_t i = 0; same && i < want.size(); ++i)
    same = want[i].type == laz_.items[i].type && want[i].size == laz_.items[i].size && want[i].version == laz_.items[i].version;
  if (!same)
    fail("laz.unsupported", laz_.where + 34, "the LASzip VLR's items do not match point format " + std::to_string(h_.format) + " with " +
                                                 std::to_string(h_.extra_bytes()) + " extra bytes as laz-perf decodes it (item versions " +
                                                 (h_.format <= 3 ? "2" : "3") + ")");
  if (laz_.chunk_size == 0) fail("laz.vlr", laz_.where + 12, "chunk size 0");
  // 2. The chunk table, then each chunk in turn.
  const std::uint64_t first_chunk = std::uint64_t(h_.point_offset) + 8;
  std::uint64_t table_offset = 0;
  std::vector<std::uint64_t> counts;
  const std::vector<std::uint64_t> sizes = read_chunk_table(first_chunk, table_offset, counts);
  prepare_output();
  std::uint64_t at = first_chunk;
  for (std::size_t i = 0; i < sizes.size() && !done_; ++i) {
    decode_chunk(i, at, sizes[i], counts[i]);
    at += sizes[i];
  }
}

void LasReader::report_facts() const {
  if (!report_) return;
  auto put = [this](const std::string& key, const std::string& value) { report_->header.emplace_back(key, value); };
  auto triple = [](const double* v) {
    std::ostringstream s;
    s.precision(15);  // a header's doubles hold ~15 significant digits; more shows binary noise
    s << v[0] << " " << v[1] << " " << v[2];
    return s.str();
  };
  report_->format = std::string(h_.compressed ? "laz" : "las") + " " + std::to_string(h_.major) + "." + std::to_string(h_.minor) +
                    " (point format " + std::to_string(h_.format) + ")";
  put("version", std::to_string(h_.major) + "." + std::to_string(h_.minor));
  put("point_format", std::to_string(h_.format));
  put("record_length", std::to_string(h_.record_length) + " (" + std::to_string(h_.extra_bytes()) + " extra bytes)");
  put("point_count", std::to_string(h_.count));
  put("scale", triple(h_.scale));
  put("offset", triple(h_.offset));
  const double lo[3] = {h_.min[0], h_.min[1], h_.min[2]}, hi[3] = {h_.max[0], h_.max[1], h_.max[2]};
  put("header_min", triple(lo));
  put("header_max", triple(hi));
  put("origin", triple(origin_));
  put("system_id", h_.system_id);
  put("software", h_.software);
  std::string names;
  for (const std::string& n : vlr_names_) names += (names.empty() ? "" : ", ") + n;
  put("vlrs", std::to_string(vlr_names_.size()) + (names.empty() ? "" : ": " + names));
  if (h_.compressed)
    put("laszip", "compressor " + std::to_string(laz_.compressor) + ", LASzip " + std::to_string(laz_.version_major) + "." +
                      std::to_string(laz_.version_minor) + ", chunk size " +
                      (laz_.chunk_size == 0xFFFFFFFFu ? std::string("variable") : std::to_string(laz_.chunk_size)));
}

void LasReader::read_meta() {
  read_header();
  read_vlrs();
  read_evlrs();
  choose_origin();
}

void LasReader::read_points() {
  if (h_.compressed) read_laz_points();
  else read_las_points();
}

PointSet LasReader::read() {
  read_meta();
  read_points();
  finish_colors();
  report_facts();
  return std::move(out_);
}

void LasReader::stream(std::size_t block_points, const std::function<void(PointSet&)>& block) {
  read_meta();
  block_ = &block, block_points_ = std::max<std::size_t>(1, block_points);
  // 1. The colours' width, as the whole read decides it (finish_colors), before any is stored.
  if (kRgbOffset[h_.format]) {
    scanning_ = true;
    read_points();
    scanning_ = done_ = false;
    shift_ = rgb_max_ > 255 ? 8 : 0;
    if (report_ && shift_ == 0) report_->warnings.push_back("colour values all <= 255: read as 8-bit, not scaled from 16-bit");
  }
  // 2. The points, a block at a time.
  read_points();
  flush_block();
  report_facts();
}

}  // namespace

PointSet decode_las(ByteView bytes, const std::string& path, const ReadOptions&, ReadReport* report) {
  // No ReadOptions apply: integer records under a checked scale and offset are always finite.
  const MemorySource src(bytes);
  return LasReader(src, path, report).read();
}

namespace {

// Runs f on the file's bytes: a regular file read piecewise, anything else (a pipe) read whole
// first, as InputFile does.
template <class F>
auto with_las_source(const std::string& path, F&& f) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st {};
  if (fd >= 0 && ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
    ::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);
    const FileSource src(fd, static_cast<std::uint64_t>(st.st_size), path);
    return f(src);
  }
  if (fd >= 0) ::close(fd);
  const InputFile file(path);
  const MemorySource src(file.bytes());
  return f(src);
}

}  // namespace

PointSet read_las(const std::string& path, const ReadOptions&, ReadReport* report) {
  return with_las_source(path, [&](const ByteSource& src) { return LasReader(src, path, report).read(); });
}

std::uint64_t las_point_count(const std::string& path) {
  return with_las_source(path, [&](const ByteSource& src) { return LasReader(src, path, nullptr).count(); });
}

void stream_las(const std::string& path, ReadReport* report, std::size_t block_points, const std::function<void(PointSet&)>& block) {
  with_las_source(path, [&](const ByteSource& src) {
    LasReader(src, path, report).stream(block_points, block);
    return 0;
  });
}

void stream_las(ByteView bytes, const std::string& path, ReadReport* report, std::size_t block_points,
                const std::function<void(PointSet&)>& block) {
  const MemorySource src(bytes);
  LasReader(src, path, report).stream(block_points, block);
}

}  // namespace qf
