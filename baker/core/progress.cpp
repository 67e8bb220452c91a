#include "core/progress.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>

namespace qf::progress {
namespace {

// What the stages said last, read by the display's thread. `shown` is checked without the lock so
// that a step or an item costs an atomic load when nobody watches.
struct State {
  std::atomic<bool> shown{false};
  std::atomic<std::size_t> done{0};
  std::mutex mutex;
  std::condition_variable stop_signal;
  bool stop = false;
  std::string step;
  std::size_t total = 0;
  std::chrono::steady_clock::time_point step_start;  // when `step` began: its time left is of its own pace
} state;

constexpr int kBarWidth = 24;
// No estimate before the step has run this long and done this share of its count: a level's first
// textures or the first rows of a sampling say little of the rest, and an estimate that jumps from
// 2 s to 3 min in the first second is worse than none.
constexpr double kEstimateAfterSeconds = 1;
constexpr double kEstimateAfterShare = 0.03;

}  // namespace

void step(const std::string& what, std::size_t total) {
  if (!state.shown.load(std::memory_order_relaxed)) return;
  std::lock_guard<std::mutex> lock(state.mutex);
  state.step = what;
  state.total = total;
  state.step_start = std::chrono::steady_clock::now();
  state.done.store(0, std::memory_order_relaxed);
}

void advance(std::size_t items) {
  if (state.shown.load(std::memory_order_relaxed)) state.done.fetch_add(items, std::memory_order_relaxed);
}

std::string time_left(double step_seconds, std::size_t done, std::size_t total) {
  if (total == 0 || done == 0 || done >= total || step_seconds < kEstimateAfterSeconds) return "";
  const double share = double(done) / double(total);
  if (share < kEstimateAfterShare) return "";
  const double left = step_seconds * (1 - share) / share;
  char text[32];
  if (left < 99.5)
    std::snprintf(text, sizeof text, "ETA %.0f s", left);
  else
    std::snprintf(text, sizeof text, "ETA %.0f min", std::max(2.0, left / 60));
  return text;
}

std::string progress_line(const std::string& command, double seconds, const std::string& step, std::size_t done,
                          std::size_t total, bool bar, double step_seconds) {
  char head[64];
  std::snprintf(head, sizeof head, ": %.0f s", seconds);
  std::string line = command + head;
  if (!step.empty()) line += ", " + step;
  if (total == 0) return line;
  if (done > total) done = total;
  if (bar) {
    const int filled = static_cast<int>(kBarWidth * done / total);
    line += " [" + std::string(filled, '#') + std::string(kBarWidth - filled, '.') + "]";
  }
  line += " " + std::to_string(done) + "/" + std::to_string(total);
  if (const std::string eta = bar ? time_left(step_seconds, done, total) : ""; !eta.empty()) line += ", " + eta;
  return line;
}

ProgressDisplay::ProgressDisplay(std::FILE* out, bool terminal, bool enabled, const std::string& command, double every_seconds) {
  if (!enabled || !out || state.shown.exchange(true)) return;  // one display at a time
  {
    std::lock_guard<std::mutex> lock(state.mutex);
    state.stop = false;
    state.step.clear();
    state.total = 0;
    state.step_start = std::chrono::steady_clock::now();
  }
  const auto start = std::chrono::steady_clock::now();
  // A terminal is redrawn often (it costs nothing there); a log gets a line every few seconds.
  const auto interval = terminal ? std::chrono::milliseconds(250)
                                 : std::chrono::milliseconds(static_cast<long long>(every_seconds * 1000));
  thread_ = std::thread([out, terminal, command, start, interval] {
    std::unique_lock<std::mutex> lock(state.mutex);
    while (!state.stop_signal.wait_for(lock, interval, [] { return state.stop; })) {
      const auto now = std::chrono::steady_clock::now();
      const double seconds = std::chrono::duration<double>(now - start).count();
      const double step_seconds = std::chrono::duration<double>(now - state.step_start).count();
      const std::string line = progress_line(command, seconds, state.step, state.done.load(std::memory_order_relaxed), state.total,
                                             terminal, step_seconds);
      if (terminal)
        std::fprintf(out, "\r\033[K%s", line.c_str());
      else
        std::fprintf(out, "%s\n", line.c_str());
      std::fflush(out);
    }
    if (terminal) std::fprintf(out, "\r\033[K"), std::fflush(out);
  });
}

ProgressDisplay::~ProgressDisplay() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(state.mutex);
    state.stop = true;
  }
  state.stop_signal.notify_all();
  thread_.join();
  state.shown.store(false);
}

}  // namespace qf::progress
