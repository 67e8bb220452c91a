// libFuzzer target: the PLY reader (decode_model on the bytes as "fuzz.ply"), then the model's invariants.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "fuzz.ply";
  qf::fuzz::read_and_check(data, size, path);
  return 0;
}
