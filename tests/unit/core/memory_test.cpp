// The memory budget (core/memory.h) and the bake's memory check (pipeline/bake.h check_bake_memory).
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "core/error.h"
#include "core/memory.h"
#include "pipeline/bake.h"

namespace qf {
namespace {

// Sets QF_MEMORY_LIMIT for one test and restores the environment after it.
class MemoryLimit {
 public:
  explicit MemoryLimit(const char* value) {
    if (const char* old = std::getenv("QF_MEMORY_LIMIT")) had_ = true, old_ = old;
    ::setenv("QF_MEMORY_LIMIT", value, 1);
  }
  ~MemoryLimit() {
    if (had_) ::setenv("QF_MEMORY_LIMIT", old_.c_str(), 1);
    else ::unsetenv("QF_MEMORY_LIMIT");
  }

 private:
  bool had_ = false;
  std::string old_;
};

TEST(Memory, ParsesByteSizes) {
  EXPECT_EQ(parse_byte_size("123"), 123u);
  EXPECT_EQ(parse_byte_size("512K"), 512u << 10);
  EXPECT_EQ(parse_byte_size("64m"), std::size_t{64} << 20);
  EXPECT_EQ(parse_byte_size("2GB"), std::size_t{2} << 30);
  EXPECT_EQ(parse_byte_size("3GiB"), std::size_t{3} << 30);
  EXPECT_EQ(parse_byte_size("1T"), std::size_t{1} << 40);
  for (const char* bad : {"", "G", "-5", "1.5G", "12X", "5 G", "1KM"}) EXPECT_THROW(parse_byte_size(bad), std::invalid_argument) << bad;
}

TEST(Memory, MachineFigureIsPositive) {
  // Whatever the machine: MemAvailable (or a cgroup's room) is read and is more than nothing.
  const MemoryBudget m = available_memory();
  if (std::getenv("QF_MEMORY_LIMIT")) GTEST_SKIP() << "QF_MEMORY_LIMIT set in the environment";
  EXPECT_NE(m.source, "unknown");
  EXPECT_GT(m.bytes, std::size_t{1} << 20);
}

TEST(Memory, LimitCapsTheBudget) {
  MemoryLimit cap("100M");
  const MemoryBudget m = available_memory();
  EXPECT_EQ(m.bytes, std::size_t{100} << 20);
  EXPECT_EQ(m.source, "QF_MEMORY_LIMIT");
}

TEST(Memory, EstimateGrowsWithPointsAndNeighbours) {
  AnalysisOptions a;
  EXPECT_GT(estimated_bake_bytes(2000000, a), estimated_bake_bytes(1000000, a));
  AnalysisOptions wide = a;
  wide.neighborhoods.k = 100;
  EXPECT_GT(estimated_bake_bytes(1000000, wide), estimated_bake_bytes(1000000, a));
  // Linear in the points: the per-point part of 2M is twice that of 1M.
  EXPECT_EQ(estimated_bake_bytes(2000000, a) - estimated_bake_bytes(0, a),
            2 * (estimated_bake_bytes(1000000, a) - estimated_bake_bytes(0, a)));
}

TEST(Memory, BakeThatDoesNotFitFailsWithTheFigures) {
  const AnalysisOptions a;
  MemoryLimit cap("1G");
  EXPECT_NO_THROW(check_bake_memory(1000, a, "small.ply"));
  try {
    check_bake_memory(10000000, a, "big.ply");
    FAIL() << "10M points fit in 1 GB";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), "bake.memory");
    EXPECT_EQ(e.file(), "big.ply");
    const std::string what = e.what();
    EXPECT_NE(what.find("10000000 points"), std::string::npos) << what;
    EXPECT_NE(what.find(format_bytes(double(estimated_bake_bytes(10000000, a)))), std::string::npos) << what;
    EXPECT_NE(what.find("1.0 GB is available (QF_MEMORY_LIMIT)"), std::string::npos) << what;
  }
}

TEST(Memory, MalformedLimitIsAUsageError) {
  MemoryLimit cap("lots");
  EXPECT_THROW(check_bake_memory(1000, AnalysisOptions{}, "x.ply"), UsageError);
}

}  // namespace
}  // namespace qf
