// libFuzzer target: the LAS/LAZ reader (the same bytes as "fuzz.las"; the header, not the name,
// says whether they are compressed), then the point set's invariants and the classification's;
// then the same bytes streamed in blocks, which must give the same points or fail alike.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "fuzz.las";
  std::optional<qf::PointSet> whole;
  try {
    qf::ReadReport report;
    whole = qf::decode_las(qf::fuzz::view(data, size), path, {}, &report);
    const qf::PointSet& p = *whole;
    qf::fuzz::check_points(p);
    QF_FUZZ_CHECK(p.size() > 0);
    QF_FUZZ_CHECK(p.scalars.size() == 1 && p.scalars[0].values.size() == p.size());
    for (float c : p.scalars[0].values) QF_FUZZ_CHECK(c >= 0 && c <= 255 && c == std::floor(c));
  } catch (const qf::InputError& e) {
    QF_FUZZ_CHECK(!e.code().empty() && e.file() == path && !e.where().empty());
  }
  // The bake's out-of-core route reads the same file a block at a time.
  qf::fuzz::check_streamed(qf::fuzz::view(data, size), path, {}, whole);
  return 0;
}
