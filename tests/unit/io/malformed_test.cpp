// Every file of tests/data/malformed is rejected with its specific error code (EXPECTED.tsv),
// names the file, and says where it broke. Run under ASan/UBSan too (label "readers").
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/error.h"
#include "io/model_io.h"
#include "test_util.h"

namespace qf {
namespace {

struct Case {
  std::string file, code;
};

std::vector<Case> load_cases() {
  std::vector<Case> cases;
  std::ifstream in(test::test_data_dir() + "/malformed/EXPECTED.tsv");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t tab = line.find('\t');
    cases.push_back({line.substr(0, tab), line.substr(tab + 1)});
  }
  return cases;
}

TEST(Malformed, CorpusIsLargeEnough) { EXPECT_GE(load_cases().size(), 25u); }

TEST(Malformed, EveryFileFailsWithItsCode) {
  for (const Case& c : load_cases()) {
    SCOPED_TRACE(c.file);
    const std::string path = test::test_data_dir() + "/malformed/" + c.file;
    try {
      read_model(path);
      ADD_FAILURE() << "accepted a malformed file";
    } catch (const InputError& e) {
      EXPECT_EQ(e.code(), c.code) << e.what();
      EXPECT_EQ(e.file(), path);
      EXPECT_FALSE(e.detail().empty());
      // Every body/tree error says where; header-less whole-file errors may not.
      if (c.code.find(".body.") != std::string::npos || c.code.rfind("qsplat.", 0) == 0) {
        EXPECT_FALSE(e.where().empty()) << e.what();
      }
    }
  }
}

TEST(Malformed, TruncationAtEveryByteNeverCrashes) {
  // Every prefix of a valid file either reads or fails with an InputError: never a crash, never
  // another exception. (ASan/UBSan make out-of-bounds reads fatal.)
  for (const char* name : {"pyr.qs", "sphere_col.qs", "pyr.ply", "tet.ply"}) {
    std::ifstream in(test::qsplat_dir() + "/" + name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    test::TempDir dir;
    const std::string ext = std::string(name).substr(std::string(name).rfind('.'));
    const std::size_t step = bytes.size() > 4000 ? 37 : 1;
    for (std::size_t n = 0; n < bytes.size(); n += step) {
      const std::string f = dir.write("cut" + ext, bytes.substr(0, n));
      try {
        read_model(f);
      } catch (const InputError&) {
      }
    }
  }
}

TEST(Malformed, BitFlipsNeverCrash) {
  // Flip each byte of small valid files (several patterns): reject cleanly or read.
  for (const char* name : {"pyr.qs", "tet.qs", "pyr.ply"}) {
    std::ifstream in(test::qsplat_dir() + "/" + name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    test::TempDir dir;
    const std::string ext = std::string(name).substr(std::string(name).rfind('.'));
    for (std::size_t i = 0; i < bytes.size(); ++i)
      for (unsigned char mask : {0x01, 0x80, 0xFF, 0x55}) {
        std::string b = bytes;
        b[i] = static_cast<char>(b[i] ^ mask);
        const std::string f = dir.write("flip" + ext, b);
        try {
          read_model(f);
        } catch (const InputError&) {
        }
      }
  }
}

}  // namespace
}  // namespace qf
