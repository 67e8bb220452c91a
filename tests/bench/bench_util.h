// Small helpers shared by the benchmarks.
#pragma once

#include <cstdlib>
#include <fstream>
#include <string>

#include "core/memory.h"
#include "io/model_io.h"
#include "shapes/shapes.h"

namespace qf::bench {

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
