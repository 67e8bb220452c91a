// The memory budget (core/memory.h) and the bake's memory check (pipeline/bake.h plan_bake_memory).
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
  const BakeOptions o;
  MemoryLimit cap("390M");  // the fixed 384 MB and room for 6 MB more: no subsample fits
  EXPECT_FALSE(plan_bake_memory(1000, o, false, "small.ply").out_of_core);
  try {
    plan_bake_memory(10000000, o, false, "big.ply");
    FAIL() << "10M points fit in 390 MB";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), "bake.memory");
    EXPECT_EQ(e.file(), "big.ply");
    const std::string what = e.what();
    EXPECT_NE(what.find("10000000 points"), std::string::npos) << what;
    const double plain = double(estimated_bake_bytes(10000000, o.analysis));
    EXPECT_NE(what.find(format_bytes(double(kBakeFixedBytes) + kPointSetMargin * (plain - double(kBakeFixedBytes)))), std::string::npos) << what;
    EXPECT_NE(what.find("390 MB is available (QF_MEMORY_LIMIT)"), std::string::npos) << what;
    EXPECT_NE(what.find("even out of core"), std::string::npos) << what;
  }
}

TEST(Memory, PointSetPastTheLimitBakesOutOfCoreMeshIsRefused) {
  BakeOptions o;
  o.max_memory = std::size_t{1} << 30;  // --max-memory 1G
  const MemoryPlan plan = plan_bake_memory(10000000, o, false, "big.ply");
  EXPECT_TRUE(plan.out_of_core);
  EXPECT_EQ(plan.limit_source, "--max-memory");
  // The subsample's estimated decomposition takes its share of the room above the fixed part.
  EXPECT_LE(double(estimated_bake_bytes(plan.subsample, o.analysis) - kBakeFixedBytes),
            kOutOfCoreSubsampleShare * double(plan.limit - kBakeFixedBytes));
  EXPECT_GT(plan.subsample, 400000u);
  EXPECT_LT(plan.subsample, 10000000u);
  EXPECT_GT(plan.batch_points, 0u);
  // Under the limit: in memory, whatever the machine has.
  EXPECT_FALSE(plan_bake_memory(100000, o, false, "small.ply").out_of_core);
  // A point set is planned with the margin for uneven density: one whose plain estimate takes 95%
  // of the limit bakes out of core, a mesh sampled into as many points in memory.
  const double per_point = double(estimated_bake_bytes(1000000, o.analysis) - estimated_bake_bytes(0, o.analysis)) / 1e6;
  const auto near = static_cast<std::size_t>(0.95 * double(o.max_memory - kBakeFixedBytes) / per_point);
  EXPECT_TRUE(plan_bake_memory(near, o, false, "scan.ply").out_of_core);
  EXPECT_FALSE(plan_bake_memory(near, o, true, "mesh.off").out_of_core);
  try {
    plan_bake_memory(10000000, o, true, "big.off");
    FAIL() << "a mesh past the limit is not streamed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), "bake.memory");
    const std::string what = e.what();
    EXPECT_NE(what.find("1.0 GB is allowed (--max-memory)"), std::string::npos) << what;
    EXPECT_NE(what.find("not streamed"), std::string::npos) << what;
  }
}

TEST(Memory, MalformedLimitIsAUsageError) {
  MemoryLimit cap("lots");
  EXPECT_THROW(plan_bake_memory(1000, BakeOptions{}, false, "x.ply"), UsageError);
}

}  // namespace
}  // namespace qf
