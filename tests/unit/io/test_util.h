// Helpers for the reader/writer tests: temporary files and paths to test data.
#pragma once

#include <string>
#include <vector>

namespace qf::test {

// A fresh, empty folder under the system temp dir, removed when the object goes away.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  // Writes `bytes` to `name` in the folder and returns the full path.
  std::string write(const std::string& name, const std::string& bytes) const;
  // Names of the files in the folder, sorted.
  std::vector<std::string> files() const;

 private:
  std::string dir_;
};

std::string qsplat_dir();     // tests/data/qsplat (QSplat vectors and their source PLY meshes)
std::string test_data_dir();  // tests/data

}  // namespace qf::test
