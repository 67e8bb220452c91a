// The region behind DeterministicHeap, and the program's replacement operator new/delete that route
// a scope's allocations into it (every other allocation goes to malloc, as the library's own would).
#include "core/deterministic_heap.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory_resource>
#include <new>
#include <stdexcept>

namespace qf {
namespace {

// The region: a pool resource (size-classed free lists, the standard library's) over a monotonic
// buffer on the mapped range, with nothing behind it (past the range: std::bad_alloc). Neither
// takes memory from elsewhere, so its layout follows the scope's requests alone. Each block is
// preceded by a header with its size and alignment, which an unsized delete needs to give it back.
struct Header {
  std::size_t bytes;  // as asked, the header and alignment padding included
  std::size_t align;
};
constexpr std::size_t kHeader = 16;  // sizeof(Header), and operator new's default alignment
static_assert(sizeof(Header) == kHeader);

struct Region {
  Region(void* mapped, std::size_t bytes)
      : base(static_cast<char*>(mapped)), reserve(bytes), range(mapped, bytes, std::pmr::null_memory_resource()), pool(&range) {}
  char* base;
  std::size_t reserve;
  std::pmr::monotonic_buffer_resource range;
  std::pmr::unsynchronized_pool_resource pool;

  bool contains(const void* p) const {
    const char* c = static_cast<const char*>(p);
    return c >= base && c < base + reserve;
  }
  void* allocate(std::size_t bytes, std::size_t align) {
    align = std::max(align, kHeader);
    if (bytes > reserve) throw std::bad_alloc();
    char* p = static_cast<char*>(pool.allocate(bytes + align, align)) + align;
    *reinterpret_cast<Header*>(p - kHeader) = {bytes + align, align};
    return p;
  }
  void release(void* p) {
    const Header h = *reinterpret_cast<const Header*>(static_cast<char*>(p) - kHeader);
    pool.deallocate(static_cast<char*>(p) - h.align, h.bytes, h.align);
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
  Region* r = new Region(base, reserve_bytes);  // before routing: the bookkeeping lives on the process heap
  region_ = r;
  t_owned = r;
  t_routed = true;
}

DeterministicHeap::~DeterministicHeap() {
  Region* r = static_cast<Region*>(region_);
  t_owned = nullptr;
  t_routed = false;
  const std::size_t reserve = r->reserve;
  void* base = r->base;
  delete r;  // the resources' destructors give their blocks back to the range, which is then unmapped
  munmap(base, reserve);
}

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
