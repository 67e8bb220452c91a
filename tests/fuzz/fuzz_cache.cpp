// libFuzzer target: the hierarchy cache file (decode_hierarchy). The first byte chooses how the rest
// is read: even, as a payload wrapped in a valid header (magic, version, key, size, checksum), so
// that the fuzzer reaches the payload's parser behind the checksum; odd, as a whole file. Where a
// hierarchy loads, the downstream step is the basis's first product: P[0]'s rows scattered through
// fine_order, and every prolongation applied to a vector of ones.
#include <Eigen/Dense>
#include <cstring>

#include "amg/hierarchy_cache.h"
#include "core/hash.h"
#include "core/sparse.h"
#include "fuzz_common.h"

namespace {

const std::string kKey = "00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff";

template <class T>
void put(std::string& s, const T& v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// The header save_hierarchy writes (amg/hierarchy_cache.cpp): magic, version 3, key, size, checksum.
std::string wrap(const std::uint8_t* payload, std::size_t n) {
  std::string file("QFAMGCH\0", 8);
  put(file, std::uint32_t{3});
  file += kKey;
  put(file, static_cast<std::uint64_t>(n));
  put(file, qf::Sha256().update(qf::ByteView(payload, n)).digest64());
  file.append(reinterpret_cast<const char*>(payload), n);
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool wrapped = (data[0] & 1) == 0;
  const std::string file = wrapped ? wrap(data + 1, size - 1) : std::string(reinterpret_cast<const char*>(data + 1), size - 1);
  std::string why;
  std::vector<qf::Vec3f> normals;
  const auto h = qf::decode_hierarchy(qf::ByteView(reinterpret_cast<const std::uint8_t*>(file.data()), file.size()), kKey,
                                      &why, &normals);
  if (!h) {
    QF_FUZZ_CHECK(!why.empty());
    return 0;
  }
  QF_FUZZ_CHECK(!h->levels.empty() && h->P.size() + 1 == h->levels.size());
  QF_FUZZ_CHECK(h->fine_order.size() == h->levels[0].size);
  QF_FUZZ_CHECK(normals.empty() || normals.size() == h->levels[0].size);
  if (!h->P.empty()) {
    const qf::SparseMatrix psi = qf::scatter_rows(h->P[0], h->fine_order);
    QF_FUZZ_CHECK(static_cast<std::size_t>(psi.rows()) == h->levels[0].size);
  }
  Eigen::VectorXd v = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(h->levels.back().size));
  for (std::size_t l = h->P.size(); l-- > 0;) v = h->P[l] * v;
  QF_FUZZ_CHECK(static_cast<std::size_t>(v.size()) == h->levels[0].size);
  return 0;
}
