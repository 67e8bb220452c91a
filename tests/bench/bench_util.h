// Small helpers shared by the benchmarks.
#pragma once

#include <cstdlib>
#include <fstream>
#include <string>

#include "io/model_io.h"
#include "shapes/shapes.h"

namespace qf::bench {

// A memory figure of this process from /proc/self/status, bytes: "VmRSS:" (resident now) or
// "VmHWM:" (peak resident so far).
inline std::size_t memory(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::strtoull(line.c_str() + 6, nullptr, 10) * 1024;
  return 0;
}

// A benchmark input: a model file (a mesh gives its vertices) or a generated shape of n points.
// `name` gets the file name or the shape name.
inline PointSet load_input(const std::string& source, std::size_t n, std::string& name) {
  name = source;
  if (source.find('.') == std::string::npos) return generate_shape(source, {n, 1});
  name = source.substr(source.find_last_of('/') + 1);
  Model m = read_model(source);
  if (!m.is_mesh) return std::move(m.points);
  PointSet p;
  p.positions = std::move(m.mesh.positions);
  return p;
}

}  // namespace qf::bench
