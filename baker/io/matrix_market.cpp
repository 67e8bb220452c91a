// Matrix Market writer.
#include "io/matrix_market.h"

#include <charconv>
#include <ostream>

#include "core/file_io.h"

namespace qf {

void write_matrix_market(const std::string& path, const SparseMatrix& m, const std::string& comment) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "%%MatrixMarket matrix coordinate real general\n";
    if (!comment.empty()) out << "% " << comment << "\n";
    out << m.rows() << " " << m.cols() << " " << m.nonZeros() << "\n";
    std::string buf;
    char num[64];
    for (Eigen::Index i = 0; i < m.outerSize(); ++i) {
      for (SparseMatrix::InnerIterator it(m, i); it; ++it) {
        buf += std::to_string(it.row() + 1);
        buf += ' ';
        buf += std::to_string(it.col() + 1);
        buf += ' ';
        const double v = it.value() == 0.0 ? 0.0 : it.value();  // no "-0"
        buf.append(num, std::to_chars(num, num + sizeof num, v).ptr);
        buf += '\n';
      }
      if (buf.size() > (1 << 16)) {
        out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
        buf.clear();
      }
    }
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  });
}

}  // namespace qf
