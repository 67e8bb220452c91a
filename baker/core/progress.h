// Progress of a long command for the person watching it: the step running now, how far it is when
// it counts items, and the time spent. The stages only name their steps (progress::step) and count
// items (progress::advance); nothing is shown unless a command holds a ProgressDisplay, so a
// library caller, a test or a batch's child process prints nothing. Progress never changes what a
// command writes to its files.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <thread>

namespace qf::progress {

// The step now running ("analysis", "level 3: textures"); `total` > 0 when it counts that many
// items. Cheap when no display is shown; call it from one thread (the command's).
void step(const std::string& what, std::size_t total = 0);

// `items` more of the step's count are done. Safe from any thread (OpenMP loops).
void advance(std::size_t items = 1);

// Shows the steps on `out` while it lives, from a thread of its own:
// - on a terminal, one line rewritten four times a second: elapsed time, step, a bar and the count
//   when the step counts, with the step's time left once it can be told (time_left); the line is
//   cleared when the display ends;
// - otherwise (a log, CI) a plain line every `every_seconds` while the command runs, so a short
//   command prints nothing and a long one shows it is alive and where.
// Only one display at a time; `enabled` false (-q) shows nothing.
class ProgressDisplay {
 public:
  ProgressDisplay(std::FILE* out, bool terminal, bool enabled, const std::string& command, double every_seconds = 5);
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

 private:
  std::thread thread_;
};

// The estimate of a counting step's time left, "ETA 12 s" (past 99 s in minutes, "ETA 4 min"),
// from the seconds the step has run and its count done of total, as if the items left take as long
// as those done; empty while it cannot be told: before 1 s and 3% of the count (the first items
// say little of the rest), without a count, or once done.
std::string time_left(double step_seconds, std::size_t done, std::size_t total);

// One line of the display, as it is printed (without the terminal's control characters): exposed
// for its unit test. With `bar` (a terminal) the count is followed by time_left(step_seconds, ...)
// where there is one; a log's line never has it (a line every few seconds is read afterwards, when
// the time left is past).
std::string progress_line(const std::string& command, double seconds, const std::string& step, std::size_t done,
                          std::size_t total, bool bar, double step_seconds = 0);

}  // namespace qf::progress
