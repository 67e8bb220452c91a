// Scratch files on disk for a job that does not fit in memory (the out-of-core bake,
// pipeline/out_of_core.h): created in $TMPDIR (or /tmp, or a folder given), removed when the
// object goes, and also when the process is stopped by SIGINT, SIGTERM or SIGHUP (a handler
// unlinks every live scratch file, then lets the signal take its course). A SIGKILL (the kernel's
// OOM killer) leaves the file behind: its name, qf-<tag>-<pid>-XXXXXX.scratch, says whose it was,
// and the next ScratchFile made in that folder removes it (its process gone, its lock free).
#pragma once

#include <cstdint>
#include <string>

namespace qf {

class ScratchFile {
 public:
  // Creates an empty file "qf-<tag>-<pid>-XXXXXX.scratch" in `dir` ($TMPDIR, else /tmp, when
  // empty). Throws std::runtime_error naming the folder where it cannot be created.
  explicit ScratchFile(const std::string& tag, const std::string& dir = "");
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  // Appends bytes at the end; returns the offset they start at. Throws std::runtime_error on a
  // short write (a full disk), naming the file.
  std::uint64_t append(const void* data, std::size_t bytes);
  // Reads `bytes` at `offset` (written before). Throws std::runtime_error on a short read.
  void read(void* data, std::size_t bytes, std::uint64_t offset) const;

  const std::string& path() const { return path_; }
  std::uint64_t size() const { return size_; }

 private:
  std::string path_;
  int fd_ = -1;
  int slot_ = -1;  // in the signal handler's table
  std::uint64_t size_ = 0;
};

// The folder scratch files go to by default: $TMPDIR if set and not empty, else /tmp.
std::string default_scratch_dir();

}  // namespace qf
