// The region behind DeterministicHeap, and the program's replacement operator new/delete that route
// a scope's allocations into it (every other allocation goes to malloc, as the library's own would).
#include "core/deterministic_heap.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>
#include <stdexcept>

namespace qf {
namespace {

// Size classes: multiples of 16 bytes up to 1 KiB, then powers of two. Each block starts with a
// 16-byte header (its class, and the distance from the block's start to the pointer handed out, for
// over-aligned requests); a freed block goes on its class's list, and the next request of that class
// takes the most recently freed one. Nothing here depends on anything outside the scope.
constexpr std::size_t kHeader = 16;
constexpr std::size_t kSmallLimit = 1024;
constexpr std::size_t kSmallClasses = kSmallLimit / 16;
constexpr std::size_t kClasses = kSmallClasses + 48;

struct Header {
  std::uint32_t size_class;
  std::uint32_t offset;  // from the block's start to the pointer handed out
  std::uint64_t unused;
};
static_assert(sizeof(Header) == kHeader);

std::size_t class_of(std::size_t bytes) {
  if (bytes <= kSmallLimit) return bytes == 0 ? 0 : (bytes - 1) / 16;
  std::size_t c = kSmallClasses, size = 2 * kSmallLimit;
  while (size < bytes) size *= 2, ++c;
  return c;
}

std::size_t class_size(std::size_t c) { return c < kSmallClasses ? 16 * (c + 1) : (2 * kSmallLimit) << (c - kSmallClasses); }

struct Region {
  char* base = nullptr;
  std::size_t reserve = 0;
  std::size_t top = 0;  // the high-water mark: blocks are carved from here when their list is empty
  void* free_list[kClasses] = {};

  bool contains(const void* p) const {
    const char* c = static_cast<const char*>(p);
    return c >= base && c < base + reserve;
  }

  void* allocate(std::size_t bytes, std::size_t align) {
    const std::size_t pad = align > kHeader ? align - kHeader : 0;
    if (bytes > reserve) throw std::bad_alloc();
    const std::size_t c = class_of(bytes + kHeader + pad);
    if (c >= kClasses) throw std::bad_alloc();
    char* block = static_cast<char*>(free_list[c]);
    if (block != nullptr) {
      free_list[c] = *reinterpret_cast<void**>(block);
    } else {
      if (class_size(c) > reserve - top) throw std::bad_alloc();
      block = base + top;
      top += class_size(c);
    }
    const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(block) + kHeader;
    char* p = reinterpret_cast<char*>(align > kHeader ? (first + align - 1) / align * align : first);
    Header* h = reinterpret_cast<Header*>(p - kHeader);
    h->size_class = static_cast<std::uint32_t>(c);
    h->offset = static_cast<std::uint32_t>(p - block);
    return p;
  }

  void release(void* p) {
    const Header* h = reinterpret_cast<const Header*>(static_cast<char*>(p) - kHeader);
    char* block = static_cast<char*>(p) - h->offset;
    const std::size_t c = h->size_class;
    *reinterpret_cast<void**>(block) = free_list[c];
    free_list[c] = block;
  }
};

// The scope's region (for frees, also while paused), and whether new allocations go to it.
thread_local Region* t_owned = nullptr;
thread_local bool t_routed = false;

void* allocate(std::size_t bytes, std::size_t align) {
  if (t_routed) return t_owned->allocate(bytes, align);
  for (;;) {
    void* p = align <= kHeader ? std::malloc(bytes == 0 ? 1 : bytes)
                               : std::aligned_alloc(align, (bytes + align - 1) / align * align);
    if (p != nullptr) return p;
    std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

void deallocate(void* p) {
  if (p == nullptr) return;
  if (t_owned != nullptr && t_owned->contains(p))
    t_owned->release(p);
  else
    std::free(p);
}

void* allocate_nothrow(std::size_t bytes, std::size_t align) noexcept {
  try {
    return allocate(bytes, align);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}

}  // namespace

DeterministicHeap::DeterministicHeap(std::size_t reserve_bytes) : region_(nullptr) {
  if (t_owned != nullptr) throw std::logic_error("DeterministicHeap scopes do not nest");
  // Address space, not memory: a smaller reserve where the system refuses the whole.
  void* base = mmap(nullptr, reserve_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  while (base == MAP_FAILED && reserve_bytes > (std::size_t{64} << 20)) {
    reserve_bytes /= 2;
    base = mmap(nullptr, reserve_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  }
  if (base == MAP_FAILED) throw std::bad_alloc();
  Region* r = new Region;  // before routing: the bookkeeping lives on the process heap
  r->base = static_cast<char*>(base);
  r->reserve = reserve_bytes;
  region_ = r;
  t_owned = r;
  t_routed = true;
}

DeterministicHeap::~DeterministicHeap() {
  Region* r = static_cast<Region*>(region_);
  t_owned = nullptr;
  t_routed = false;
  munmap(r->base, r->reserve);
  delete r;
}

std::size_t DeterministicHeap::peak_bytes() const { return static_cast<const Region*>(region_)->top; }
std::size_t DeterministicHeap::reserve_bytes() const { return static_cast<const Region*>(region_)->reserve; }

DeterministicHeap::Pause::Pause() : held_(t_routed ? t_owned : nullptr) { t_routed = false; }
DeterministicHeap::Pause::~Pause() { t_routed = held_ != nullptr; }

}  // namespace qf

// The replaceable global allocation functions ([new.delete]): all of them, so that no form falls
// back to the library's own, which would hand a region pointer to free() or the reverse.
void* operator new(std::size_t n) { return qf::allocate(n, 0); }
void* operator new[](std::size_t n) { return qf::allocate(n, 0); }
void* operator new(std::size_t n, std::align_val_t a) { return qf::allocate(n, static_cast<std::size_t>(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return qf::allocate(n, static_cast<std::size_t>(a)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return qf::allocate_nothrow(n, 0); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return qf::allocate_nothrow(n, 0); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return qf::allocate_nothrow(n, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return qf::allocate_nothrow(n, static_cast<std::size_t>(a));
}
void operator delete(void* p) noexcept { qf::deallocate(p); }
void operator delete[](void* p) noexcept { qf::deallocate(p); }
void operator delete(void* p, std::size_t) noexcept { qf::deallocate(p); }
void operator delete[](void* p, std::size_t) noexcept { qf::deallocate(p); }
void operator delete(void* p, std::align_val_t) noexcept { qf::deallocate(p); }
void operator delete[](void* p, std::align_val_t) noexcept { qf::deallocate(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { qf::deallocate(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { qf::deallocate(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { qf::deallocate(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { qf::deallocate(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { qf::deallocate(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { qf::deallocate(p); }
