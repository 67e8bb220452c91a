// libFuzzer target: the XYZ and PWN reader (the same bytes as "fuzz.xyz" and as "fuzz.pwn", which
// requires normals), then the point set's invariants.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string xyz = "fuzz.xyz", pwn = "fuzz.pwn";
  qf::fuzz::read_and_check(data, size, xyz);
  qf::fuzz::read_and_check(data, size, pwn);
  return 0;
}
