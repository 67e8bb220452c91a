// The progress display: what a person watching a long bake reads, and silence where nobody asked.
#include "core/progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

namespace qf::progress {
namespace {

std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, f)) s.append(buffer, n);
  return s;
}

TEST(Progress, LineNamesTheStepTimeAndCount) {
  EXPECT_EQ(progress_line("qf-bake bake", 12.4, "analysis", 0, 0, false), "qf-bake bake: 12 s, analysis");
  EXPECT_EQ(progress_line("qf-bake bake", 3, "level 6: textures", 40, 120, false), "qf-bake bake: 3 s, level 6: textures 40/120");
  // A bar of 24 cells, a third full; a count past its total is shown as the total.
  EXPECT_EQ(progress_line("q", 0, "t", 40, 120, true), "q: 0 s, t [########................] 40/120");
  EXPECT_EQ(progress_line("q", 0, "t", 500, 120, true), "q: 0 s, t [########################] 120/120");
}

TEST(Progress, TimeLeftFollowsThePaceOfTheItemsDone) {
  // A quarter done in 4 s: three quarters left at that pace.
  EXPECT_EQ(time_left(4, 25, 100), "ETA 12 s");
  EXPECT_EQ(time_left(10, 1, 2), "ETA 10 s");
  // Past 99 s in minutes.
  EXPECT_EQ(time_left(60, 10, 100), "ETA 9 min");
  EXPECT_EQ(time_left(100, 50, 100), "ETA 2 min");
}

TEST(Progress, NoTimeLeftUntilItCanBeTold) {
  EXPECT_EQ(time_left(0.9, 50, 100), "") << "before a second";
  EXPECT_EQ(time_left(30, 2, 100), "") << "before 3% of the count";
  EXPECT_EQ(time_left(5, 0, 100), "") << "nothing done";
  EXPECT_EQ(time_left(5, 100, 100), "") << "done";
  EXPECT_EQ(time_left(5, 3, 0), "") << "no count";
  EXPECT_EQ(time_left(1, 3, 100), "ETA 32 s") << "both bars passed";
}

TEST(Progress, TerminalLineEndsWithTheTimeLeftAndALogsLineDoesNot) {
  EXPECT_EQ(progress_line("q", 8, "t", 40, 120, true, 4), "q: 8 s, t [########................] 40/120, ETA 8 s");
  EXPECT_EQ(progress_line("q", 8, "t", 40, 120, false, 4), "q: 8 s, t 40/120");
  EXPECT_EQ(progress_line("q", 8, "t", 40, 120, true, 0.5), "q: 8 s, t [########................] 40/120") << "too early";
  EXPECT_EQ(progress_line("q", 8, "analysis", 0, 0, true, 4), "q: 8 s, analysis") << "a step without a count";
}

TEST(Progress, LogGetsPlainLinesWithTheCurrentStep) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  {
    const ProgressDisplay shown(log, false, true, "cmd", 0.02);
    step("textures", 10);
    advance(3);
    advance(4);
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
  }
  const std::string s = contents(log);
  std::fclose(log);
  EXPECT_NE(s.find(", textures 7/10\n"), std::string::npos) << s;
  EXPECT_EQ(s.find('\r'), std::string::npos) << "no terminal control in a log";
}

TEST(Progress, TerminalLineIsRedrawnAndClearedAtTheEnd) {
  std::FILE* tty = std::tmpfile();
  ASSERT_NE(tty, nullptr);
  {
    const ProgressDisplay shown(tty, true, true, "cmd");
    step("analysis");
    std::this_thread::sleep_for(std::chrono::milliseconds(600));
  }
  const std::string s = contents(tty);
  std::fclose(tty);
  EXPECT_NE(s.find("\r\033[Kcmd: 0 s, analysis"), std::string::npos) << s;
  EXPECT_EQ(s.find('\n'), std::string::npos);
  ASSERT_GE(s.size(), 4u);
  EXPECT_EQ(s.substr(s.size() - 4), "\r\033[K") << "the last line is wiped, so the summary starts clean";
}

TEST(Progress, QuietOrNoDisplayPrintsNothing) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  step("before any display", 5);  // no display: a no-op
  advance(2);
  {
    const ProgressDisplay quiet(log, false, false, "cmd", 0.01);
    step("analysis", 3);
    std::this_thread::sleep_for(std::chrono::milliseconds(80));
  }
  EXPECT_EQ(contents(log), "");
  std::fclose(log);
}

TEST(Progress, OneDisplayAtATime) {
  std::FILE* first = std::tmpfile();
  std::FILE* second = std::tmpfile();
  {
    const ProgressDisplay a(first, false, true, "a", 0.02);
    const ProgressDisplay b(second, false, true, "b", 0.02);
    step("x");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_NE(contents(first), "");
  EXPECT_EQ(contents(second), "");
  std::fclose(first);
  std::fclose(second);
}

}  // namespace
}  // namespace qf::progress
