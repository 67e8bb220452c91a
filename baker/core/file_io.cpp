// Whole-file reads and atomic (temp + rename) writes.
#include "core/file_io.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace qf {

InputFile::InputFile(const std::string& path, Access access) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError("file.unreadable", path, "", "is a directory, expected a file");
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError("file.unreadable", path, "", std::string("cannot open: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    size_ = static_cast<std::size_t>(st.st_size);
    void* m = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | (access == Access::kWhole ? MAP_POPULATE : 0), fd, 0);
    if (m != MAP_FAILED) {
      map_ = m;
      if (access == Access::kStreamed) ::madvise(map_, size_, MADV_SEQUENTIAL);
      ::close(fd);
      return;
    }
  }
  // Not mappable (pipe, empty file, special file): read until EOF.
  std::uint8_t chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw InputError("file.unreadable", path, at_byte(buffer_.size()), std::string("read error: ") + std::strerror(err));
    }
    if (n == 0) break;
    buffer_.insert(buffer_.end(), chunk, chunk + n);
  }
  ::close(fd);
}

InputFile::~InputFile() {
  if (map_) ::munmap(map_, size_);
}

void InputFile::release(std::size_t offset) const {
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  const std::size_t end = std::min(offset, size_) / page * page;
  if (map_ && end > 0) ::madvise(map_, end, MADV_DONTNEED);
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw_output_error("cannot create output file '" + tmp + "'", errno);
      write(out);
      out.flush();
      if (!out) throw_output_error("cannot write output file '" + tmp + "'", errno ? errno : EIO);
    }
    // fsync before rename so a crash cannot leave a renamed but empty file behind; on NFS a full
    // disk or quota may show first here.
    const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || ::fsync(fd) != 0) {
      const int err = errno;
      if (fd >= 0) ::close(fd);
      throw_output_error("cannot write output file '" + tmp + "'", err);
    }
    ::close(fd);
    std::filesystem::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

void write_bytes_atomically(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  });
}

namespace {

// True for a pid that names no live process on this machine. A zombie (exited, not yet reaped:
// in containers whose init reaps nothing, for ever) counts as gone.
bool process_gone(const std::string& digits) {
  if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return false;
  if (::kill(static_cast<pid_t>(std::stol(digits)), 0) != 0) return errno == ESRCH;
  std::ifstream stat("/proc/" + digits + "/stat");
  std::string line;
  std::getline(stat, line);
  const std::size_t paren = line.rfind(')');  // "pid (comm) S ...": comm may hold spaces
  return paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] == 'Z';
}

// A staging folder's writer holds an exclusive lock on its ".lock" file while it works; the lock
// goes with the process (kill -9 included), so a lock we can take marks an abandoned folder.
bool staging_abandoned(const std::filesystem::path& dir, const std::string& pid) {
  const int fd = ::open((dir / ".lock").c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return process_gone(pid);  // killed before the lock existed
  const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  ::close(fd);
  return free;
}

}  // namespace

void remove_stale_temporaries(const std::string& dir) {
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::size_t tmp = name.rfind(".tmp-");
    const std::size_t dash = name.rfind('-');
    const bool staging = name.size() > 1 && name[0] == '.' && dash != std::string::npos && it->is_directory(ec);
    if (staging) {
      if (staging_abandoned(it->path(), name.substr(dash + 1))) std::filesystem::remove_all(it->path(), ec);
    } else if (tmp != std::string::npos && process_gone(name.substr(tmp + 5))) {
      std::filesystem::remove(it->path(), ec);
    }
  }
}

std::string file_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace qf
