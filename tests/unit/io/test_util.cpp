// Temporary folders and data paths for tests.
#include "test_util.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace qf::test {

TempDir::TempDir() {
  std::string templ = (std::filesystem::temp_directory_path() / "qf-test-XXXXXX").string();
  if (!::mkdtemp(templ.data())) throw std::runtime_error("mkdtemp failed");
  dir_ = templ;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

std::string TempDir::write(const std::string& name, const std::string& bytes) const {
  const std::string p = path(name);
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

std::vector<std::string> TempDir::files() const {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir_)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

std::string qsplat_dir() { return QF_TEST_DATA "/qsplat"; }
std::string test_data_dir() { return QF_TEST_DATA; }

}  // namespace qf::test
