// libFuzzer target: the QSplat .qs decoder (decode_qsplat, from memory), then the point set's
// invariants: every leaf has a position, a normal and a radius.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "fuzz.qs";
  try {
    qf::ReadReport report;
    const qf::PointSet p = qf::decode_qsplat(qf::fuzz::view(data, size), path, &report);
    qf::fuzz::check_points(p);
    QF_FUZZ_CHECK(p.normals.size() == p.size() && p.radii.size() == p.size());
  } catch (const qf::InputError& e) {
    QF_FUZZ_CHECK(!e.code().empty() && e.file() == path);
  }
  return 0;
}
