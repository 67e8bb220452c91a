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
//   when the step counts; the line is cleared when the display ends;
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

// One line of the display, as it is printed (without the terminal's control characters): exposed
// for its unit test.
std::string progress_line(const std::string& command, double seconds, const std::string& step, std::size_t done,
                          std::size_t total, bool bar);

}  // namespace qf::progress
