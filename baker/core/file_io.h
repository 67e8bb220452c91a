// Whole-file reads and atomic writes (write to a temporary name in the same folder, then rename),
// so that no reader ever sees a half-written output, even if the process is killed.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace qf {

// A read-only view of bytes (a file's content, or a buffer).
class ByteView {
 public:
  ByteView() = default;
  ByteView(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  ByteView(const std::vector<std::uint8_t>& v) : data_(v.data()), size_(v.size()) {}  // NOLINT: implicit on purpose
  const std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::uint8_t operator[](std::size_t i) const { return data_[i]; }

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

// The whole content of an input file. Regular files are memory-mapped (pre-faulted): on the
// project's VMs that is ~8x faster than read() into fresh memory, whose page faults dominate.
// Other files (pipes) are read into a buffer. Throws InputError("file.unreadable").
// Note: a regular file truncated by another process while mapped raises SIGBUS on access.
// Streamed (a file read once, front to back, larger than memory may hold): mapped without
// pre-faulting, read ahead, and release() drops the pages already read from the process' memory.
class InputFile {
 public:
  enum class Access { kWhole, kStreamed };
  explicit InputFile(const std::string& path, Access access = Access::kWhole);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  ByteView bytes() const { return map_ ? ByteView(static_cast<const std::uint8_t*>(map_), size_) : ByteView(buffer_); }
  // Streamed: the bytes before `offset` will not be read again (their pages leave the process'
  // resident memory; a read of them would fault them in anew). No-op for a buffer.
  void release(std::size_t offset) const;

 private:
  void* map_ = nullptr;
  std::size_t size_ = 0;
  std::vector<std::uint8_t> buffer_;
};

// Calls `write` with a stream on "<path>.tmp-<pid>" next to `path`, flushes, fsyncs and renames
// it over `path`. If `write` throws, or the stream fails, the temporary file is removed and the
// exception propagates; `path` is left untouched.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// write_file_atomically with these bytes as the whole content.
void write_bytes_atomically(const std::string& path, const std::vector<std::uint8_t>& bytes);

// Removes what killed writers left in `dir`: temporary files "<name>.tmp-<pid>" whose process is
// gone from this machine, and staging folders ".<tag>-<pid>" (written inside output folders before
// they were replaced whole, core/output_folder.h) whose ".lock" is free. The cache calls it before
// each save, OutputFolder on the folder it replaces, so a rerun after a kill starts clean.
void remove_stale_temporaries(const std::string& dir);

// Lower-case extension without the dot ("ply" for "a/b.PLY"), or "" if none.
std::string file_extension(const std::string& path);

}  // namespace qf
