// Shared pieces of the libFuzzer targets: a byte view of the input, and the invariants every model
// a reader returns must keep (checked as the "cheap downstream step": bounds, array sizes, indices).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/file_io.h"
#include "core/types.h"
#include "io/model_io.h"

namespace qf::fuzz {

inline ByteView view(const std::uint8_t* data, std::size_t size) { return ByteView(data, size); }

// A broken invariant is a bug: abort, so that libFuzzer keeps the input as a crash.
#define QF_FUZZ_CHECK(cond)                                                             \
  do {                                                                                  \
    if (!(cond)) {                                                                      \
      std::fprintf(stderr, "fuzz invariant failed: %s (%s:%d)\n", #cond, __FILE__, __LINE__); \
      std::abort();                                                                     \
    }                                                                                   \
  } while (0)

// Per-point arrays are empty or as long as the positions; every position is finite (readers
// reject or drop non-finite ones); the bounds of a non-empty set are finite.
inline void check_points(const PointSet& p) {
  const std::size_t n = p.positions.size();
  QF_FUZZ_CHECK(p.normals.empty() || p.normals.size() == n);
  QF_FUZZ_CHECK(p.colors.empty() || p.colors.size() == n);
  QF_FUZZ_CHECK(p.radii.empty() || p.radii.size() == n);
  Bounds b;
  for (const Vec3f& x : p.positions) {
    QF_FUZZ_CHECK(is_finite(x));
    b.add(x);
  }
  for (float r : p.radii) QF_FUZZ_CHECK(r >= 0 && std::isfinite(r));
  for (const Vec3f& v : p.normals) QF_FUZZ_CHECK(is_finite(v));
  QF_FUZZ_CHECK(n == 0 || !b.empty());
}

// The same for meshes, and every triangle names existing vertices.
inline void check_mesh(const TriangleMesh& m) {
  const std::size_t n = m.positions.size();
  QF_FUZZ_CHECK(m.normals.empty() || m.normals.size() == n);
  QF_FUZZ_CHECK(m.colors.empty() || m.colors.size() == n);
  Bounds b;
  for (const Vec3f& x : m.positions) {
    QF_FUZZ_CHECK(is_finite(x));
    b.add(x);
  }
  QF_FUZZ_CHECK(n == 0 || !b.empty());
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) QF_FUZZ_CHECK(t[k] < n);
}

inline void check_model(const Model& m) {
  if (m.is_mesh) check_mesh(m.mesh);
  else check_points(m.points);
}

// Reads the bytes as `path` says (by extension). A file with non-finite coordinates is read again
// with drop_nonfinite, so that the removal and reindexing are exercised too. InputError is the
// expected answer to a bad file; any other exception escapes and libFuzzer reports it.
inline void read_and_check(const std::uint8_t* data, std::size_t size, const std::string& path) {
  ReadOptions options;
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      ReadReport report;
      const Model m = decode_model(view(data, size), path, options, &report);
      check_model(m);
      return;
    } catch (const InputError& e) {
      const std::string& code = e.code();
      QF_FUZZ_CHECK(!code.empty() && e.file() == path);
      if (code.size() < 10 || code.compare(code.size() - 10, 10, ".nonfinite") != 0) return;
      options.drop_nonfinite = true;
    }
  }
  QF_FUZZ_CHECK(!"a file read with drop_nonfinite still reports a non-finite coordinate");
}

// A file that streams (LAS/LAZ, a PLY of points) read 7 points at a time: the blocks are the
// whole read's points in order, with the same attributes, or the stream fails with InputError
// where the whole read did (`whole`: the whole read's set; nullopt where it threw InputError).
// UsageError says the file does not stream (a PLY with faces), which only a set read whole as a
// point set contradicts.
inline void check_streamed(ByteView bytes, const std::string& path, const ReadOptions& options, const std::optional<PointSet>& whole) {
  constexpr std::size_t kBlock = 7;
  PointSet got;
  bool failed = false;
  try {
    stream_point_set(bytes, path, options, nullptr, kBlock, [&](PointSet& b) {
      QF_FUZZ_CHECK(b.size() > 0 && b.size() <= kBlock);
      check_points(b);
      got.positions.insert(got.positions.end(), b.positions.begin(), b.positions.end());
      got.normals.insert(got.normals.end(), b.normals.begin(), b.normals.end());
      got.radii.insert(got.radii.end(), b.radii.begin(), b.radii.end());
      got.colors.insert(got.colors.end(), b.colors.begin(), b.colors.end());
      if (got.scalars.empty()) got.scalars = std::vector<ScalarField>(b.scalars.size());
      QF_FUZZ_CHECK(got.scalars.size() == b.scalars.size());
      for (std::size_t k = 0; k < b.scalars.size(); ++k)
        got.scalars[k].values.insert(got.scalars[k].values.end(), b.scalars[k].values.begin(), b.scalars[k].values.end());
    });
  } catch (const InputError& e) {
    QF_FUZZ_CHECK(e.file() == path);
    failed = true;
  } catch (const UsageError&) {
    QF_FUZZ_CHECK(!whole);
    return;
  }
  QF_FUZZ_CHECK(failed == !whole);
  if (!whole) return;
  QF_FUZZ_CHECK(got.positions == whole->positions);
  QF_FUZZ_CHECK(got.normals == whole->normals);
  QF_FUZZ_CHECK(got.radii == whole->radii);
  QF_FUZZ_CHECK(got.colors == whole->colors);
  QF_FUZZ_CHECK(got.scalars.size() == whole->scalars.size());
  for (std::size_t k = 0; k < got.scalars.size(); ++k) QF_FUZZ_CHECK(got.scalars[k].values == whole->scalars[k].values);
}

}  // namespace qf::fuzz
