// Hierarchy cache files: a fixed header (magic, version, key, payload size and checksum) and the
// hierarchy's arrays, little-endian.
#include "amg/hierarchy_cache.h"

#include <cstring>
#include <filesystem>
#include <ostream>

#include "core/error.h"
#include "core/file_io.h"
#include "core/hash.h"

namespace qf {
namespace {

constexpr char kMagic[8] = {'Q', 'F', 'A', 'M', 'G', 'C', 'H', '\0'};
constexpr std::uint32_t kVersion = 3;  // bump when the file layout or the algorithms change (3: SHA-256 keys)

std::uint64_t checksum(const std::string& payload) {
  return Sha256().update(ByteView(reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size())).digest64();
}

template <class T>
void put(std::string& s, const T& v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
void put_array(std::string& s, const T* data, std::size_t n) {
  put(s, static_cast<std::uint64_t>(n));
  if (n) s.append(reinterpret_cast<const char*>(data), n * sizeof(T));  // an empty vector's data() may be null
}

class Reader {
 public:
  Reader(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  template <class T>
  bool get(T& v) {
    if (sizeof v > n_ - pos_) return false;
    std::memcpy(&v, p_ + pos_, sizeof v);
    pos_ += sizeof v;
    return true;
  }
  template <class T>
  bool get_array(std::vector<T>& out, std::uint64_t max_count) {
    std::uint64_t n = 0;
    // Divide rather than multiply: n * sizeof(T) wraps for n near 2^64 and would pass the check.
    if (!get(n) || n > max_count || n > (n_ - pos_) / sizeof(T)) return false;
    out.resize(static_cast<std::size_t>(n));
    if (n) std::memcpy(out.data(), p_ + pos_, static_cast<std::size_t>(n) * sizeof(T));  // data() may be null when empty
    pos_ += static_cast<std::size_t>(n) * sizeof(T);
    return true;
  }
  bool done() const { return pos_ == n_; }

 private:
  const std::uint8_t* p_;
  std::size_t n_, pos_ = 0;
};

std::string path_of(const std::string& dir, const std::string& key) { return dir + "/" + key + ".qfamg"; }

// 1. The header: magic, version, key, payload size and checksum. Returns null when it holds (the
//    payload then lies at [start, start + size)), else why not.
const char* check_header(ByteView bytes, const std::string& key, std::size_t& start, std::uint64_t& size) {
  Reader header(bytes.data(), bytes.size());
  char magic[sizeof kMagic];
  std::uint32_t version = 0;
  std::string stored_key(key.size(), '\0');
  std::uint64_t sum = 0;
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return "not a cache file";
  for (char& c : magic) header.get(c);
  if (!header.get(version)) return "truncated";
  if (version != kVersion) return "another format version";
  for (char& c : stored_key)
    if (!header.get(c)) return "truncated";
  if (stored_key != key) return "another key";
  if (!header.get(size) || !header.get(sum)) return "truncated";
  start = sizeof kMagic + sizeof version + key.size() + 2 * sizeof(std::uint64_t);
  if (bytes.size() - start != size) return "truncated";
  const std::string payload(reinterpret_cast<const char*>(bytes.data() + start), static_cast<std::size_t>(size));
  if (checksum(payload) != sum) return "corrupt (checksum)";
  return nullptr;
}

// 2. The counts and the levels. A level's size counts entries stored below (fine_order, P's rows):
//    no more than the payload's bytes.
bool read_levels(Reader& r, std::uint64_t size, AmgHierarchy& h) {
  std::uint64_t components = 0, isolated = 0, levels = 0;
  if (!r.get(components) || !r.get(isolated) || !r.get(levels) || levels == 0 || levels > 64) return false;
  h.components = components, h.isolated = isolated;
  for (std::uint64_t l = 0; l < levels; ++l) {
    std::uint64_t s = 0;
    AmgLevel lv;
    if (!r.get(s) || !r.get(lv.theta) || !r.get(lv.ratio) || s > size) return false;
    lv.size = s;
    h.levels.push_back(lv);
  }
  return true;
}

// 3. The fine order: a permutation of the points, since the basis scatters P[0]'s rows through it
//    (sparse.h scatter_rows).
bool read_fine_order(Reader& r, AmgHierarchy& h) {
  if (!r.get_array(h.fine_order, h.levels[0].size) || h.fine_order.size() != h.levels[0].size) return false;
  std::vector<char> seen(h.fine_order.size(), 0);
  for (std::uint32_t i : h.fine_order) {
    if (i >= seen.size() || seen[i]) return false;
    seen[i] = 1;
  }
  return true;
}

// 4. P of level l (l >= 1): rows of level l - 1, columns of level l, a well-formed compressed matrix.
bool read_prolongation(Reader& r, std::size_t l, std::uint64_t size, AmgHierarchy& h) {
  std::uint64_t rows = 0, cols = 0;
  std::vector<std::int32_t> outer, inner;
  std::vector<double> values;
  if (!r.get(rows) || !r.get(cols) || rows != h.levels[l - 1].size || cols != h.levels[l].size) return false;
  if (!r.get_array(outer, rows + 1) || !r.get_array(inner, size) || !r.get_array(values, size)) return false;
  if (outer.size() != rows + 1 || inner.size() != values.size() || outer.front() != 0 ||
      outer.back() != static_cast<std::int32_t>(inner.size()))
    return false;
  for (std::size_t i = 0; i + 1 < outer.size(); ++i)
    if (outer[i] > outer[i + 1]) return false;
  for (std::int32_t c : inner)
    if (c < 0 || static_cast<std::uint64_t>(c) >= cols) return false;
  // Columns strictly increasing within a row, as Eigen's compressed matrices (which wrote them) keep them.
  for (std::size_t i = 0; i + 1 < outer.size(); ++i)
    for (std::int32_t k = outer[i] + 1; k < outer[i + 1]; ++k)
      if (inner[static_cast<std::size_t>(k - 1)] >= inner[static_cast<std::size_t>(k)]) return false;
  h.P.push_back(from_rows(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols), outer, inner, values));
  return true;
}

}  // namespace

std::string hierarchy_cache_key(const PointSet& points, const AnalysisOptions& ao, const AmgOptions& amg) {
  Sha256 h;
  h.value(kVersion);
  h.value(static_cast<std::uint64_t>(points.size()));
  h.update(ByteView(reinterpret_cast<const std::uint8_t*>(points.positions.data()), points.positions.size() * sizeof(Vec3f)));
  h.value(static_cast<std::uint8_t>(points.has_normals()));
  h.update(ByteView(reinterpret_cast<const std::uint8_t*>(points.normals.data()), points.normals.size() * sizeof(Vec3f)));
  h.value(ao.neighborhoods.k), h.value(ao.neighborhoods.epsilon), h.value(ao.neighborhoods.max_neighbors);
  h.value(static_cast<int>(ao.classifier.kind)), h.value(ao.classifier.alpha), h.value(ao.classifier.beta);
  h.value(ao.classifier.epsilon);
  h.value(amg.theta), h.value(amg.target_ratio_min), h.value(amg.target_ratio_max), h.value(amg.ratio_tries);
  h.value(static_cast<std::uint64_t>(amg.stop_size)), h.value(amg.max_levels);
  // Only when given, so that the keys of hierarchies made without them stay as they were.
  if (!amg.target_sizes.empty()) {
    h.value(static_cast<std::uint64_t>(amg.target_sizes.size()));
    for (std::size_t t : amg.target_sizes) h.value(static_cast<std::uint64_t>(t));
  }
  return h.hex();
}

void save_hierarchy(const std::string& dir, const std::string& key, const AmgHierarchy& h,
                    const std::vector<Vec3f>& normals) {
  std::string payload;
  put(payload, static_cast<std::uint64_t>(h.components));
  put(payload, static_cast<std::uint64_t>(h.isolated));
  put(payload, static_cast<std::uint64_t>(h.levels.size()));
  for (const AmgLevel& l : h.levels) put(payload, static_cast<std::uint64_t>(l.size)), put(payload, l.theta), put(payload, l.ratio);
  put_array(payload, h.fine_order.data(), h.fine_order.size());
  for (const SparseMatrix& p : h.P) {
    put(payload, static_cast<std::uint64_t>(p.rows()));
    put(payload, static_cast<std::uint64_t>(p.cols()));
    put_array(payload, p.outerIndexPtr(), static_cast<std::size_t>(p.rows()) + 1);
    put_array(payload, p.innerIndexPtr(), static_cast<std::size_t>(p.nonZeros()));
    put_array(payload, p.valuePtr(), static_cast<std::size_t>(p.nonZeros()));
  }
  put_array(payload, normals.data(), normals.size());
  std::filesystem::create_directories(dir);
  // Half-written entries of killed bakes ("<key>.qfamg.tmp-<pid>", tens of MB each) whose process
  // is gone: nothing else would ever remove them.
  remove_stale_temporaries(dir);
  write_file_atomically(path_of(dir, key), [&](std::ostream& out) {
    std::string header(kMagic, sizeof kMagic);
    put(header, kVersion);
    header += key;
    put(header, static_cast<std::uint64_t>(payload.size()));
    put(header, checksum(payload));
    out << header << payload;
  });
}

std::optional<AmgHierarchy> load_hierarchy(const std::string& dir, const std::string& key, std::string* why,
                                           std::vector<Vec3f>* normals) {
  auto fail = [&](const char* reason) -> std::optional<AmgHierarchy> {
    if (why) *why = reason;
    return std::nullopt;
  };
  const std::string path = path_of(dir, key);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return fail("missing");
  std::optional<InputFile> file;
  try {
    file.emplace(path);
  } catch (const InputError&) {
    return fail("unreadable");
  }
  return decode_hierarchy(file->bytes(), key, why, normals);
}

// The hierarchy in a cache file's bytes, or nullopt with `why` (when given) saying why not: not a
// cache file, another version or key, truncated, or corrupt. Counts, sizes and indices are checked
// before they are used (tests/fuzz feeds it arbitrary bytes). `normals` receives the stored point
// normals (empty if none were).
std::optional<AmgHierarchy> decode_hierarchy(ByteView bytes, const std::string& key, std::string* why,
                                             std::vector<Vec3f>* normals) {
  auto fail = [&](const char* reason) -> std::optional<AmgHierarchy> {
    if (why) *why = reason;
    return std::nullopt;
  };
  std::size_t start = 0;
  std::uint64_t size = 0;
  if (const char* reason = check_header(bytes, key, start, size)) return fail(reason);
  Reader r(bytes.data() + start, static_cast<std::size_t>(size));
  AmgHierarchy h;
  if (!read_levels(r, size, h) || !read_fine_order(r, h)) return fail("corrupt");
  for (std::size_t l = 1; l < h.levels.size(); ++l)
    if (!read_prolongation(r, l, size, h)) return fail("corrupt");
  // 5. The point normals (none, or one per point), and nothing after them.
  std::vector<Vec3f> stored;
  if (!r.get_array(stored, h.levels[0].size) || (!stored.empty() && stored.size() != h.levels[0].size)) return fail("corrupt");
  if (!r.done()) return fail("corrupt");
  if (normals) *normals = std::move(stored);
  return h;
}

}  // namespace qf
