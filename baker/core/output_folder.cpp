// An output folder replaced whole, under a lock beside it (output_folder.h).
#include "core/output_folder.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/file_io.h"

namespace qf {

namespace fs = std::filesystem;

namespace {

// QF_TEST_SWAP (tests only; tests/cli/kill_test.sh): "two-renames" takes the path of file systems
// without RENAME_EXCHANGE; "stop:POINT" stops the process (SIGSTOP) at POINT ("filled": the new
// folder written, nothing swapped; "aside": the old folder set aside, the new not yet in; "swapped":
// the new in place, the old not yet removed), so that a test can SIGKILL it exactly there.
bool test_swap(const char* word) {
  const char* v = std::getenv("QF_TEST_SWAP");
  return v && std::strstr(v, word) != nullptr;
}
void test_stop(const char* point) {
  if (test_swap((std::string("stop:") + point).c_str())) ::raise(SIGSTOP);
}

// Takes the lock on `lock_path` without waiting. The lock file is removed by its holder on release;
// a process that opened it just before that would lock a file no longer there, so the lock counts
// only while the path still names the file locked (else open again). `fresh`: this call created
// the file, so no writer died holding it (a clean release removes it) and nothing needs repair.
int take_lock(const fs::path& lock_path, const std::string& shown, bool& fresh) {
  for (int attempt = 0; attempt < 64; ++attempt) {
    int fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    fresh = fd >= 0;
    if (fd < 0 && errno == EEXIST) fd = ::open(lock_path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0 && errno == ENOENT) continue;  // removed by its holder between the two opens
    if (fd < 0) throw_output_error("cannot create the lock file '" + lock_path.string() + "'", errno);
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      if (err == EWOULDBLOCK)
        throw BusyError(shown + ": another bake is writing this folder now (it holds the lock " + lock_path.string() +
                        "); nothing was written: wait for it to end, or bake into another folder");
      throw_output_error("cannot lock '" + lock_path.string() + "'", err);
    }
    struct stat held {}, named {};
    if (::fstat(fd, &held) == 0 && ::stat(lock_path.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
        held.st_ino == named.st_ino)
      return fd;
    ::close(fd);
  }
  throw OutputError("cannot lock '" + lock_path.string() + "': its lock file keeps being replaced");
}

// The folder `path` names: absolute, normalised, symlinks resolved (a symlinked output folder is
// replaced where it lives, and the link stays).
fs::path resolved_folder(const std::string& path) {
  if (path.empty()) throw UsageError("the output folder's name is empty");
  fs::path p = fs::absolute(path).lexically_normal();
  if (!p.has_filename()) p = p.parent_path();  // "out/" and "out/." name "out"
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(p, ec);
  if (!ec) p = resolved;
  if (p == p.root_path() || !p.has_filename() || p.filename() == "..")
    throw UsageError("'" + path + "' cannot be an output folder: a bake replaces its output folder whole");
  const fs::path cwd = fs::weakly_canonical(fs::current_path(ec), ec);
  if (!ec) {
    const auto mismatch = std::mismatch(p.begin(), p.end(), cwd.begin(), cwd.end());
    if (mismatch.first == p.end())
      throw UsageError("'" + path + "' is the current folder or holds it: a bake replaces its output folder whole; name a folder of its own");
  }
  if (fs::exists(p, ec) && !fs::is_directory(p, ec))
    throw UsageError("'" + path + "' is a file: the output must be a folder");
  return p;
}

// Flushes a folder's entries (the names renamed into it) to the disk; best effort (a power cut,
// not a kill, is what it guards against).
void sync_folder(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// `src` recreated at `dst` without copying bytes: folders made anew, files hard-linked (copied
// where the file system has no hard links), symlinks as they are; FIFOs, sockets and devices are
// not carried.
void link_tree(const fs::path& src, const fs::path& dst) {
  std::error_code ec;
  const fs::file_status s = fs::symlink_status(src, ec);
  if (fs::is_symlink(s)) {
    fs::copy_symlink(src, dst);
  } else if (fs::is_directory(s)) {
    fs::create_directory(dst);
    for (const fs::directory_entry& e : fs::directory_iterator(src)) link_tree(e.path(), dst / e.path().filename());
  } else if (fs::is_regular_file(s)) {
    if (::link(src.c_str(), dst.c_str()) != 0) {
      if (errno != EPERM && errno != EXDEV && errno != EMLINK && errno != EOPNOTSUPP)
        throw_output_error("cannot carry '" + src.string() + "' into the new folder", errno);
      fs::copy_file(src, dst);
    }
  }
}

// Swaps the two folders in one step (renameat2 RENAME_EXCHANGE). False where the file system
// cannot (NFS, some FUSE file systems: EINVAL; old kernels: ENOSYS); other failures throw.
bool exchange(const fs::path& a, const fs::path& b) {
  if (test_swap("two-renames")) return false;
  if (::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0) return true;
  const int err = errno;
  if (err == EINVAL || err == ENOSYS || err == EOPNOTSUPP) return false;
  std::error_code ec;
  fs::remove_all(a, ec);
  throw_output_error("cannot swap '" + a.string() + "' in for '" + b.string() + "'", err);
}

void rename_or_throw(const fs::path& from, const fs::path& to) {
  if (::rename(from.c_str(), to.c_str()) != 0)
    throw_output_error("cannot rename '" + from.string() + "' to '" + to.string() + "'", errno);
}

}  // namespace

OutputFolder::OutputFolder(const std::string& path) : path_(path), folder_(resolved_folder(path)) {
  try {
    fs::create_directories(folder_.parent_path());
  } catch (const fs::filesystem_error& e) {
    throw_output_error("cannot create the folder '" + folder_.parent_path().string() + "'", e.code().value());
  }
  lock_path_ = sibling("lock", "");
  bool fresh = false;
  lock_ = take_lock(lock_path_, path_, fresh);
  try {
    // A lock file left by a dead writer says what a scan of the parent would find; without one,
    // scanning it (thousands of asset folders in a batch's) for every asset would cost O(N^2).
    if (!fresh) repair();
    std::error_code ec;
    if (fs::is_directory(folder_, ec)) remove_stale_temporaries(folder_.string());
  } catch (...) {
    ::close(lock_);
    throw;
  }
}

OutputFolder::~OutputFolder() {
  if (lock_ < 0) return;
  // While still held (see take_lock); kept when a sibling could not be removed (an NFS client's
  // ".nfs" files of open ones), so that the next owner scans for it.
  if (clean_) ::unlink(lock_path_.c_str());
  ::close(lock_);
}

fs::path OutputFolder::sibling(const char* kind, const std::string& pid) const {
  return folder_.parent_path() / ("." + folder_.filename().string() + ".qf-" + kind + (pid.empty() ? "" : "-" + pid));
}

void OutputFolder::repair() {
  // 1. The siblings a dead writer left (no live one can own any: it would hold the lock).
  const std::string prefix = "." + folder_.filename().string() + ".qf-";
  std::vector<fs::path> olds, others;
  std::error_code ec;
  for (fs::directory_iterator it(folder_.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() + 4 || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string kind = name.substr(prefix.size(), 4), pid = name.substr(prefix.size() + 4);
    if ((kind != "new-" && kind != "old-") || pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    (kind == "old-" ? olds : others).push_back(it->path());
  }
  // 2. A two-rename swap killed between its renames: the folder is missing and the old content
  // aside; put it back (the old bake), then drop the rest.
  if (!fs::exists(folder_, ec) && !olds.empty()) {
    rename_or_throw(olds.front(), folder_);
    olds.erase(olds.begin());
  }
  for (const std::vector<fs::path>* list : {&olds, &others})
    for (const fs::path& p : *list) {
      fs::remove_all(p, ec);
      clean_ = clean_ && !fs::exists(fs::symlink_status(p, ec));
    }
}

void OutputFolder::replace(const std::function<void(const std::string& staging)>& fill,
                           const std::function<bool(const std::string& name)>& keep) {
  const std::string pid = std::to_string(::getpid());
  const fs::path staging = sibling("new", pid);
  std::error_code ec;
  fs::remove_all(staging, ec);
  // 1. The new content, and what the old folder holds that the writer did not make.
  try {
    if (::mkdir(staging.c_str(), 0755) != 0) throw_output_error("cannot create the folder '" + staging.string() + "'", errno);
    fill(staging.string());
    if (fs::is_directory(folder_, ec))
      for (const fs::directory_entry& e : fs::directory_iterator(folder_)) {
        const std::string name = e.path().filename().string();
        if (keep(name) && !fs::exists(fs::symlink_status(staging / name))) link_tree(e.path(), staging / name);
      }
    sync_folder(staging);
  } catch (...) {
    fs::remove_all(staging, ec);
    clean_ = clean_ && !fs::exists(fs::symlink_status(staging, ec));
    throw;
  }
  test_stop("filled");
  // 2. The swap: one atomic exchange where the file system has it, else two renames.
  if (!fs::exists(folder_, ec)) {
    rename_or_throw(staging, folder_);
  } else if (exchange(staging, folder_)) {
    test_stop("swapped");
    fs::remove_all(staging, ec);  // now the old content
    clean_ = clean_ && !fs::exists(fs::symlink_status(staging, ec));
  } else {
    const fs::path old = sibling("old", pid);
    try {
      rename_or_throw(folder_, old);
    } catch (...) {
      fs::remove_all(staging, ec);
      throw;
    }
    test_stop("aside");
    if (::rename(staging.c_str(), folder_.c_str()) != 0) {
      const int err = errno;
      ::rename(old.c_str(), folder_.c_str());
      fs::remove_all(staging, ec);
      throw_output_error("cannot rename '" + staging.string() + "' to '" + folder_.string() + "'", err);
    }
    test_stop("swapped");
    fs::remove_all(old, ec);
    clean_ = clean_ && !fs::exists(fs::symlink_status(old, ec));
  }
  sync_folder(folder_.parent_path());
}

}  // namespace qf
