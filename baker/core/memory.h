// Large arrays on transparent huge pages. On the project's VMs a first touch of fresh memory
// costs ~2.7 ms per MB in page faults (measured: 64 MB memset 172 ms; 100 ms with huge pages),
// which is a large share of the analysis of a million points. Asking for huge pages before the
// first touch cuts the number of faults 512-fold where the kernel grants them.
#pragma once

#include <malloc.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace qf {

// Reserves capacity for n elements and, for 2 MiB or more, advises the kernel to back the
// buffer with huge pages. Call before filling the vector.
template <class T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
  v.reserve(n);
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const std::size_t bytes = v.capacity() * sizeof(T);
  if (bytes < kHuge) return;
  const auto begin = reinterpret_cast<std::uintptr_t>(v.data());
  const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1), last = (begin + bytes) & ~(kHuge - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

// For executables, at start-up: keep freed memory in the process for reuse instead of returning
// it to the kernel (no mmap'ed chunks, no heap trimming), so the stages' temporaries are recycled
// instead of faulted in afresh. Measured on 1M points: AMG hierarchy 6.7 s -> 3.4 s, analysis
// 7.5 s -> 5.8 s. The cost is that a process keeps its peak heap until it exits.
inline void keep_freed_memory() {
  ::mallopt(M_MMAP_MAX, 0);
  ::mallopt(M_TRIM_THRESHOLD, -1);
  ::mallopt(M_TOP_PAD, 64 << 20);
}

// A memory figure of this process from /proc/self/status, bytes: "VmRSS:" (resident now) or
// "VmHWM:" (peak resident so far); 0 where /proc is not available.
inline std::size_t process_memory(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::strtoull(line.c_str() + 6, nullptr, 10) * 1024;
  return 0;
}

// The memory a new allocation of this process can count on, bytes, and where the figure comes
// from: the least of /proc/meminfo's MemAvailable, the memory cgroup's limit less its usage
// (page cache that can be dropped, inactive_file, counted as free; cgroup v2 memory.max or v1
// memory.limit_in_bytes, from this process' cgroup up to the hierarchy's root) and the variable
// QF_MEMORY_LIMIT (bytes, or with a K, M, G or T suffix, powers of 1024), which lets a farm
// reserve memory for other jobs and tests trigger the check cheaply. `source` names the winner:
// "MemAvailable", "cgroup limit" or "QF_MEMORY_LIMIT". SIZE_MAX (source "unknown") when none can
// be read. Throws std::invalid_argument for a malformed QF_MEMORY_LIMIT.
struct MemoryBudget {
  std::size_t bytes = SIZE_MAX;
  std::string source = "unknown";
};
MemoryBudget available_memory();

// "123", "512K", "64M", "2G", "1T" (case-insensitive, an optional trailing B or iB) -> bytes.
// Throws std::invalid_argument naming `text` for anything else.
std::size_t parse_byte_size(const std::string& text);

// A byte count for messages: "812 MB", "9.6 GB" (powers of 1024).
std::string format_bytes(double bytes);

}  // namespace qf
