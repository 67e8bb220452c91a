// libFuzzer target: the PLY reader (decode_model on the bytes as "fuzz.ply"), then the model's invariants; a PLY of points
// also streamed in blocks, which must give the same points or fail alike.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "fuzz.ply";
  qf::fuzz::read_and_check(data, size, path);
  // A PLY of points streams to an out-of-core bake: the same points a block at a time, or the same failure.
  std::optional<qf::PointSet> whole;
  try {
    qf::Model m = qf::decode_ply(qf::fuzz::view(data, size), path);
    if (m.is_mesh) return 0;  // a mesh does not stream
    whole = std::move(m.points);
  } catch (const qf::InputError&) {
  }
  qf::fuzz::check_streamed(qf::fuzz::view(data, size), path, {}, whole);
  return 0;
}
