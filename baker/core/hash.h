// Content hashes (SHA-256, OpenSSL): the batch's asset keys, the hierarchy cache's keys and
// checksums, and hierarchy fingerprints.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/file_io.h"

namespace qf {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  Sha256& update(ByteView bytes);
  // A string with its length in front, so that ("ab","c") and ("a","bc") hash differently.
  Sha256& update_field(const std::string& s);
  // A plain value's bytes (numbers, PODs: the machine's layout, little-endian here).
  template <class T>
  Sha256& value(const T& v) {
    return update(ByteView(reinterpret_cast<const std::uint8_t*>(&v), sizeof v));
  }
  std::string hex();         // 64 lower-case hex digits; ends the hash
  std::uint64_t digest64();  // the digest's first 8 bytes, big-endian; ends the hash

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// SHA-256 of a file's whole content (InputFile: throws InputError file.unreadable).
std::string sha256_of_file(const std::string& path);

}  // namespace qf
