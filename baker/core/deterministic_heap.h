// A heap whose addresses depend on nothing but the allocations made in it.
//
// Some library code orders objects by their addresses where its own keys tie: CGAL's advancing-front
// reconstruction keeps its border edges in a set ordered by (priority, edge pointer), and many
// edges share the same constant "stand-by" priority. With the process heap, those addresses depend
// on everything the process allocated and freed before (earlier stages, other threads, a batch's
// other assets), so the same points gave different meshes at 1 and 2 threads. Inside a
// DeterministicHeap, the C++ allocations (operator new, so every standard container) of the thread
// that made it come from a private region, placed by the sequence of allocations and frees made in
// the scope alone: the same code on the same input sees the same address order on every run.
#pragma once

#include <cstddef>

namespace qf {

class DeterministicHeap {
 public:
  // Reserves `reserve_bytes` of address space (pages are used only as touched; halved down to
  // 64 MB while the system refuses it) and routes this thread's operator new into it until
  // destruction. Scopes do not nest. An allocation past the reserve throws std::bad_alloc.
  explicit DeterministicHeap(std::size_t reserve_bytes);
  ~DeterministicHeap();
  DeterministicHeap(const DeterministicHeap&) = delete;
  DeterministicHeap& operator=(const DeterministicHeap&) = delete;

  // Nothing allocated in the scope may outlive it (the region is unmapped). Results that must:
  // allocate them while a Pause is alive (the process heap again, for this thread).
  class Pause {
   public:
    Pause();
    ~Pause();
    Pause(const Pause&) = delete;
    Pause& operator=(const Pause&) = delete;

   private:
    void* held_;
  };

  std::size_t reserve_bytes() const;  // the region's size (less than asked where the system refused that)

 private:
  void* region_;
};

}  // namespace qf
