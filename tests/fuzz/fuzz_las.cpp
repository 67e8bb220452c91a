// libFuzzer target: the LAS/LAZ reader (the same bytes as "fuzz.las"; the header, not the name,
// says whether they are compressed), then the point set's invariants and the classification's.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "fuzz.las";
  try {
    qf::ReadReport report;
    const qf::PointSet p = qf::decode_las(qf::fuzz::view(data, size), path, {}, &report);
    qf::fuzz::check_points(p);
    QF_FUZZ_CHECK(p.size() > 0);
    QF_FUZZ_CHECK(p.scalars.size() == 1 && p.scalars[0].values.size() == p.size());
    for (float c : p.scalars[0].values) QF_FUZZ_CHECK(c >= 0 && c <= 255 && c == std::floor(c));
  } catch (const qf::InputError& e) {
    QF_FUZZ_CHECK(!e.code().empty() && e.file() == path && !e.where().empty());
  }
  return 0;
}
