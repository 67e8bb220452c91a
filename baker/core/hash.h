// Content hashes (SHA-256, OpenSSL): what the batch compares to decide that an asset is unchanged.
#pragma once

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
  std::string hex();  // 64 lower-case hex digits; ends the hash

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// SHA-256 of a file's whole content (InputFile: throws InputError file.unreadable).
std::string sha256_of_file(const std::string& path);

}  // namespace qf
