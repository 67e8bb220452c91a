// Shared pieces of the readers: a whitespace tokenizer that tracks line numbers, number parsing,
// and dropping of points/vertices with non-finite coordinates.
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/types.h"
#include "io/model_io.h"

namespace qf::io {

// Splits text into whitespace-separated tokens. Lines are counted from 1.
class Tokenizer {
 public:
  Tokenizer(const char* begin, const char* end, std::size_t first_line = 1)
      : p_(begin), end_(end), line_(first_line) {}

  // Next token on any line; empty view at end of input.
  std::string_view next() {
    skip_space(true);
    return take();
  }
  // Next token on the current line only; empty view at end of line or input.
  std::string_view next_on_line() {
    skip_space(false);
    return take();
  }
  // Moves past the end of the current line.
  void skip_line() {
    while (p_ < end_ && *p_ != '\n') ++p_;
    if (p_ < end_) {
      ++p_;
      ++line_;
    }
  }
  bool at_end() {
    skip_space(true);
    return p_ >= end_;
  }
  std::size_t line() const { return line_; }
  const char* position() const { return p_; }

 private:
  void skip_space(bool cross_lines) {
    while (p_ < end_) {
      const char c = *p_;
      if (c == '\n') {
        if (!cross_lines) return;
        ++line_;
      } else if (c != ' ' && c != '\t' && c != '\r' && c != '\f' && c != '\v') {
        return;
      }
      ++p_;
    }
  }
  std::string_view take() {
    const char* s = p_;
    while (p_ < end_ && !is_space(*p_)) ++p_;
    return {s, static_cast<std::size_t>(p_ - s)};
  }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

  const char* p_;
  const char* end_;
  std::size_t line_;
};

// Parses the whole token as a number; false if it is not one (or has trailing characters).
inline bool parse_double(std::string_view t, double& out) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
  return r.ec == std::errc() && r.ptr == t.data() + t.size() && !t.empty();
}
inline bool parse_float(std::string_view t, float& out) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
  return r.ec == std::errc() && r.ptr == t.data() + t.size() && !t.empty();
}
inline bool parse_int64(std::string_view t, long long& out) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
  return r.ec == std::errc() && r.ptr == t.data() + t.size() && !t.empty();
}

// Shows a token in an error message, shortened and with control bytes escaped.
std::string quote_token(std::string_view t);

// Collects the indices of elements with non-finite coordinates. Either throws at the first one
// (default) or remembers it for removal, as ReadOptions says.
class NonFiniteFilter {
 public:
  NonFiniteFilter(const std::string& path, const ReadOptions& options) : path_(path), options_(options) {}
  // Call for each position; `where` is evaluated only on error.
  template <class Where>
  void check(std::size_t index, Vec3f p, const char* code, Where&& where) {
    if (is_finite(p)) return;
    if (!options_.drop_nonfinite)
      throw InputError(code, path_, where(),
                       "non-finite coordinate (NaN or Inf) in point " + std::to_string(index) +
                           "; pass --drop-nonfinite to drop such points");
    dropped_.push_back(index);
  }
  bool any() const { return !dropped_.empty(); }
  // Removes the recorded points from every per-point array of `points`, whose first point is
  // point `first` of the file (a streamed block; 0 for a whole read), and forgets them: a block
  // read after holds none of them.
  void apply(PointSet& points, ReadReport* report, std::size_t first = 0);
  // Removes the recorded vertices and every triangle that uses one; reindexes the rest.
  void apply(TriangleMesh& mesh, ReadReport* report) const;

 private:
  const std::string& path_;
  const ReadOptions& options_;
  std::vector<std::size_t> dropped_;  // increasing
};

}  // namespace qf::io
