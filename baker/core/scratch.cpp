// Scratch files, removed on destruction and on SIGINT / SIGTERM / SIGHUP.
#include "core/scratch.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace qf {
namespace {

// The signal handler may only call async-signal-safe functions: the live files' names are kept in
// fixed buffers, each slot marked live by an atomic flag, so the handler reads no std::string and
// takes no lock.
constexpr int kSlots = 16;
constexpr std::size_t kPathMax = 4096;
char g_paths[kSlots][kPathMax];
std::atomic<int> g_live[kSlots];
std::mutex g_mutex;  // slot allocation and handler installation (not used by the handler)
bool g_installed = false;
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[3];

void remove_scratch_and_reraise(int sig) {
  for (int s = 0; s < kSlots; ++s)
    if (g_live[s].load()) ::unlink(g_paths[s]);
  // The signal's own course: the handler that was there before ours (a default one terminates
  // the process with this signal, so the parent sees how it ended).
  for (int k = 0; k < 3; ++k)
    if (kSignals[k] == sig) ::sigaction(sig, &g_previous[k], nullptr);
  ::raise(sig);
}

void install_handlers() {
  if (g_installed) return;
  struct sigaction action {};
  action.sa_handler = remove_scratch_and_reraise;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  for (int k = 0; k < 3; ++k) {
    struct sigaction old {};
    ::sigaction(kSignals[k], nullptr, &old);
    // An ignored signal (nohup) stays ignored.
    if (old.sa_handler == SIG_IGN) continue;
    g_previous[k] = old;
    ::sigaction(kSignals[k], &action, nullptr);
  }
  g_installed = true;
}

// Removes the scratch files "qf-<tag>-<pid>-XXXXXX.scratch" in `folder` left by processes that
// are gone (a SIGKILL, the OOM killer: no handler runs). Gone means kill(pid, 0) finds no such
// process here and no process anywhere holds the file's lock: a $TMPDIR shared by several
// machines may hold a live file of a pid that is free on this one.
void remove_dead_scratch(const std::string& folder) {
  DIR* d = ::opendir(folder.c_str());
  if (!d) return;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    constexpr std::size_t kSuffix = 15;  // "-XXXXXX.scratch"
    if (name.rfind("qf-", 0) != 0 || name.size() < 3 + kSuffix + 2 || name.compare(name.size() - 8, 8, ".scratch") != 0) continue;
    const std::string head = name.substr(0, name.size() - kSuffix);  // "qf-<tag>-<pid>"
    const std::string digits = head.substr(head.rfind('-') + 1);
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    if (::kill(static_cast<pid_t>(std::stol(digits)), 0) == 0 || errno != ESRCH) continue;
    const std::string path = folder + "/" + name;
    const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) ::unlink(path.c_str());
    ::close(fd);
  }
  ::closedir(d);
}

}  // namespace

std::string default_scratch_dir() {
  const char* t = std::getenv("TMPDIR");
  return t && *t ? std::string(t) : std::string("/tmp");
}

ScratchFile::ScratchFile(const std::string& tag, const std::string& dir) {
  const std::string folder = dir.empty() ? default_scratch_dir() : dir;
  std::string name = folder + "/qf-" + tag + "-" + std::to_string(::getpid()) + "-XXXXXX.scratch";
  if (name.size() >= kPathMax) throw std::runtime_error("scratch folder name too long: " + folder);
  std::lock_guard<std::mutex> lock(g_mutex);
  for (int s = 0; s < kSlots && slot_ < 0; ++s)
    if (!g_live[s].load()) slot_ = s;
  if (slot_ < 0) throw std::logic_error("ScratchFile: more than 16 scratch files at once");
  install_handlers();
  remove_dead_scratch(folder);
  fd_ = ::mkstemps(name.data(), 8);  // 8 = strlen(".scratch")
  if (fd_ < 0)
    throw std::runtime_error("cannot create a scratch file in " + folder + " (" + std::strerror(errno) +
                             "); set TMPDIR to a folder with room");
  ::flock(fd_, LOCK_EX);  // held while the file lives: remove_dead_scratch leaves it alone
  path_ = name;
  std::memcpy(g_paths[slot_], name.c_str(), name.size() + 1);
  g_live[slot_].store(1);
}

ScratchFile::~ScratchFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!path_.empty()) ::unlink(path_.c_str());
  std::lock_guard<std::mutex> lock(g_mutex);
  if (slot_ >= 0) g_live[slot_].store(0);
}

std::uint64_t ScratchFile::append(const void* data, std::size_t bytes) {
  const std::uint64_t at = size_;
  const char* p = static_cast<const char*>(data);
  std::size_t done = 0;
  while (done < bytes) {
    const ssize_t w = ::pwrite(fd_, p + done, bytes - done, static_cast<off_t>(at + done));
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0)
      throw std::runtime_error("writing scratch file " + path_ + ": " + (w < 0 ? std::strerror(errno) : "disk full"));
    done += static_cast<std::size_t>(w);
  }
  size_ += bytes;
  return at;
}

void ScratchFile::read(void* data, std::size_t bytes, std::uint64_t offset) const {
  char* p = static_cast<char*>(data);
  std::size_t done = 0;
  while (done < bytes) {
    const ssize_t r = ::pread(fd_, p + done, bytes - done, static_cast<off_t>(offset + done));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) throw std::runtime_error("reading scratch file " + path_ + ": " + (r < 0 ? std::strerror(errno) : "short file"));
    done += static_cast<std::size_t>(r);
  }
}

}  // namespace qf
