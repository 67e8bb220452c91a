// The batch scheduler: one forked child process per asset, `jobs` at a time, their pipes polled,
// their ends reaped with their peak memory (wait4), and the progress display (pipeline/batch.h says
// why children).
#include <fcntl.h>
#include <omp.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/file_io.h"
#include "pipeline/batch_parts.h"

namespace qf::batch {
namespace {

struct Child {
  std::size_t entry = 0;  // in the state's entries
  pid_t pid = -1;
  int result_fd = -1, log_fd = -1;
  std::string result, log;
  Clock::time_point start;
};

void write_all(int fd, const std::string& s) {
  std::size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

// Forks the child that bakes `a`; its standard error goes to `log_fd`, its result to `result_fd`.
Child start_child(const BatchAsset& a, const std::string& key, const BatchOptions& o, int threads, std::size_t entry) {
  int result[2], log[2];
  if (::pipe2(result, O_CLOEXEC) != 0 || ::pipe2(log, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  const pid_t parent = ::getpid();
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("cannot fork: ") + std::strerror(errno));
  if (pid == 0) {
    // A child outlives no parent: a killed batch takes its bakes with it.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(128 + SIGKILL);
    ::dup2(log[1], 1);
    ::dup2(log[1], 2);
    omp_set_num_threads(threads);
    Json out;
    const int code = bake_in_child(a, key, o, out);
    write_all(result[1], out.dump());
    ::_exit(code);  // no atexit handlers or stdio flushes of the parent's state
  }
  ::close(result[1]);
  ::close(log[1]);
  Child c;
  c.entry = entry;
  c.pid = pid;
  c.result_fd = result[0];
  c.log_fd = log[0];
  c.start = Clock::now();
  return c;
}

// Reads what is there; closes and marks -1 at end of file.
void drain(int& fd, std::string& into) {
  if (fd < 0) return;
  char buf[65536];
  const ssize_t n = ::read(fd, buf, sizeof buf);
  if (n > 0) {
    into.append(buf, static_cast<std::size_t>(n));
  } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
    ::close(fd);
    fd = -1;
  }
}

std::string last_line(const std::string& log) {
  std::string s = log;
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  const std::size_t nl = s.rfind('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

// Fills the asset's report entry from its finished child; returns its status.
AssetStatus finish_child(Child& c, Json& entry) {
  int status = 0;
  rusage usage{};
  while (::wait4(c.pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  entry["seconds"] = round_to(since(c.start), 3);
  entry["peak_mb"] = round_to(static_cast<double>(usage.ru_maxrss) / 1024.0, 1);
  const Json result = Json::parse(c.result, nullptr, false);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && result.is_object() && result.contains("levels")) {
    entry["exit_code"] = 0;
    std::size_t primitives = 0, texels = 0;
    for (const Json& l : result["levels"]) primitives += l["primitives"].get<std::size_t>(), texels += l["texels"].get<std::size_t>();
    entry.update(result);
    entry["primitives"] = primitives;
    entry["texels"] = texels;
    return AssetStatus::kBaked;
  }
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    entry["exit_code"] = 128 + sig;
    entry["error"] = {{"code", "crashed"}, {"message", std::string("the bake was killed by signal ") + std::to_string(sig) + " (" +
                                                           strsignal(sig) + ")" + (c.log.empty() ? "" : "; last output: " + last_line(c.log))}};
  } else {
    entry["exit_code"] = WEXITSTATUS(status);
    if (result.is_object() && result.contains("error")) entry["error"] = result["error"];
    else entry["error"] = {{"code", "internal"}, {"message", "the bake ended without a result; last output: " + last_line(c.log)}};
  }
  return AssetStatus::kFailed;
}

// Waits (at most 250 ms) for output of the running children and reads it.
void poll_children(std::vector<Child>& running) {
  std::vector<pollfd> fds;
  for (const Child& c : running)
    for (int fd : {c.result_fd, c.log_fd})
      if (fd >= 0) fds.push_back({fd, POLLIN, 0});
  if (!fds.empty() && ::poll(fds.data(), fds.size(), 250) < 0 && errno != EINTR) throw std::runtime_error("poll failed");
  for (Child& c : running) {
    for (const pollfd& p : fds) {
      if (!(p.revents & (POLLIN | POLLHUP | POLLERR))) continue;
      if (p.fd == c.result_fd) drain(c.result_fd, c.result);
      else if (p.fd == c.log_fd) drain(c.log_fd, c.log);
    }
  }
}

}  // namespace

void bake_queue(const BatchManifest& m, const std::vector<std::size_t>& selected, std::deque<std::size_t> queue,
                const BatchOptions& o, int threads, BatchState& state, Progress& progress) {
  std::vector<Child> running;
  bool stopping = false;
  while (!queue.empty() || !running.empty()) {
    // 1. Start children up to `jobs`; once stopping, what is still queued is skipped.
    while (!stopping && !queue.empty() && static_cast<int>(running.size()) < std::max(1, o.jobs)) {
      const std::size_t i = queue.front();
      queue.pop_front();
      running.push_back(start_child(m.assets[selected[i]], state.keys[i], o, threads, i));
    }
    if (stopping)
      for (std::size_t i : queue) state.settle(i, AssetStatus::kSkipped, progress);
    if (stopping) queue.clear();
    // 2. Show who is baking, and read what they wrote.
    std::vector<std::string> names;
    for (const Child& c : running) names.push_back(state.entries[c.entry]["name"]);
    progress.line(state.done, state.counts, names);
    poll_children(running);
    // 3. Reap the children whose pipes are closed.
    for (std::size_t k = 0; k < running.size();) {
      Child& c = running[k];
      if (c.result_fd >= 0 || c.log_fd >= 0) {
        ++k;
        continue;
      }
      const AssetStatus s = finish_child(c, state.entries[c.entry]);
      if (s == AssetStatus::kFailed && !o.keep_going) stopping = true;
      state.settle(c.entry, s, progress);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
    }
  }
  progress.end();
}

void BatchState::settle(std::size_t i, AssetStatus s, Progress& progress) {
  status[i] = s;
  ++counts[static_cast<std::size_t>(s)];
  progress.finished(entries[i], s, ++done);
}

void Progress::finished(const Json& e, AssetStatus status, std::size_t done) {
  if (o_.quiet || !out_) return;
  if (o_.terminal) return;  // the status line says it
  if (status == AssetStatus::kUpToDate) return;  // summed up at the end: a rerun of thousands stays readable
  std::fprintf(out_, "qf-bake batch: [%zu/%zu] %s %s", done, total_, asset_status_name(status), e["name"].get<std::string>().c_str());
  if (status == AssetStatus::kBaked)
    std::fprintf(out_, " (%.2f s, %zu levels, %zu primitives, peak %.0f MB)", e["seconds"].get<double>(), e["levels"].size(),
                 e["primitives"].get<std::size_t>(), e["peak_mb"].get<double>());
  if (status == AssetStatus::kFailed) std::fprintf(out_, ": %s", e["error"]["message"].get<std::string>().c_str());
  std::fprintf(out_, "\n");
  std::fflush(out_);
}

void Progress::line(std::size_t done, const std::array<std::size_t, kAssetStatusCount>& counts, const std::vector<std::string>& running) {
  if (o_.quiet || !out_ || !o_.terminal) return;
  std::string names;
  for (const std::string& n : running) names += (names.empty() ? "" : ", ") + n;
  auto count = [&](AssetStatus s) { return counts[static_cast<std::size_t>(s)]; };
  std::fprintf(out_, "\r\033[K[%zu/%zu] %zu baked, %zu up to date, %zu failed, %.0f s%s%s", done, total_, count(AssetStatus::kBaked),
               count(AssetStatus::kUpToDate), count(AssetStatus::kFailed), since(start_), names.empty() ? "" : " | baking: ", names.c_str());
  std::fflush(out_);
}

void Progress::end() {
  if (!o_.quiet && out_ && o_.terminal) std::fprintf(out_, "\r\033[K"), std::fflush(out_);
}

}  // namespace qf::batch
