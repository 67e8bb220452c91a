// Matrix Market coordinate files (NIST format), so any tool can load and check a sparse matrix.
#pragma once

#include <string>

#include "analysis/stiffness.h"

namespace qf {

// Writes every stored entry ("coordinate real general", 1-based indices), values in their
// shortest round-trip decimal form; atomically (temporary name, then rename).
void write_matrix_market(const std::string& path, const SparseMatrix& m, const std::string& comment = "");

}  // namespace qf
