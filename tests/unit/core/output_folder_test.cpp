// The output folder (core/output_folder.h): replaced whole with a user's files carried across, one
// owner at a time, and what a killed writer left repaired by the next owner.
#include "core/output_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "core/file_io.h"
#include "../io/test_util.h"

namespace qf {
namespace {

namespace fs = std::filesystem;

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void put(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& o) { o << text; });
}

TEST(OutputFolder, ReplacesTheFolderWholeAndKeepsWhatTheCallerKeeps) {
  test::TempDir dir;
  const std::string out = dir.path("out");
  {
    OutputFolder f(out);
    f.replace([](const std::string& s) { put(s + "/a.glb", "old a"), put(s + "/b.glb", "old b"); },
              [](const std::string&) { return false; });
  }
  put(out + "/notes.txt", "mine");
  {
    OutputFolder f(out);
    f.replace([](const std::string& s) { put(s + "/a.glb", "new a"); }, [](const std::string& name) { return name != "b.glb"; });
  }
  EXPECT_EQ(read(out + "/a.glb"), "new a");
  EXPECT_FALSE(fs::exists(out + "/b.glb"));  // the old bake's, not kept
  EXPECT_EQ(read(out + "/notes.txt"), "mine");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"out"});  // no lock file, no sibling left
}

TEST(OutputFolder, ASecondOwnerIsRefusedAndAFailedFillChangesNothing) {
  test::TempDir dir;
  const std::string out = dir.path("out");
  OutputFolder first(out);
  try {
    OutputFolder second(out);
    FAIL() << "a second owner was let in";
  } catch (const BusyError& e) {
    EXPECT_NE(std::string(e.what()).find("another bake is writing this folder"), std::string::npos) << e.what();
  }
  EXPECT_THROW(first.replace([](const std::string& s) { put(s + "/a.glb", "x"), throw std::runtime_error("stop"); },
                             [](const std::string&) { return true; }),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(dir.files(), std::vector<std::string>{".out.qf-lock"});  // only the lock, while held
}

TEST(OutputFolder, TheNextOwnerRepairsWhatAKilledWriterLeft) {
  test::TempDir dir;
  const std::string out = dir.path("out");
  // A two-rename swap killed between its renames: the old folder aside, the new one complete,
  // and the writer's lock file (free: the kernel released its lock).
  dir.write(".out.qf-lock", "");
  fs::create_directories(dir.path(".out.qf-old-999999"));
  put(dir.path(".out.qf-old-999999/a.glb"), "old");
  fs::create_directories(dir.path(".out.qf-new-999999"));
  put(dir.path(".out.qf-new-999999/a.glb"), "new");
  fs::create_directories(dir.path(".out.qf-new-12x"));  // not a writer's name: left alone
  { OutputFolder f(out); }
  EXPECT_EQ(read(out + "/a.glb"), "old");
  EXPECT_EQ(dir.files(), (std::vector<std::string>{".out.qf-new-12x", "out"}));
}

TEST(OutputFolder, PathsThatCannotBeReplacedAreUsageErrors) {
  test::TempDir dir;
  dir.write("file", "x");
  EXPECT_THROW(OutputFolder(dir.path("file")), UsageError);
  EXPECT_THROW(OutputFolder("/"), UsageError);
  EXPECT_THROW(OutputFolder("."), UsageError);  // the folder a shell stands in
}

}  // namespace
}  // namespace qf
