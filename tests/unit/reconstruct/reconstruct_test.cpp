// The reconstruction peer (reconstruct/reconstruct.h) gives the same mesh for the same points,
// whatever the process allocated before it and on whichever thread it runs; the heap it runs in
// (core/deterministic_heap.h) lays out its blocks by the scope's own allocations alone.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/deterministic_heap.h"
#include "reconstruct/reconstruct.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

// A heap with a history: blocks of many sizes, every other one freed (what earlier stages leave).
std::vector<void*> fragment_heap() {
  std::vector<void*> kept;
  for (int i = 0; i < 200000; ++i) {
    void* p = std::malloc(16 + std::size_t(i * 37 % 200));
    if (i % 2 == 0) std::free(p); else kept.push_back(p);
  }
  return kept;
}

TEST(Reconstruct, SameMeshWhateverTheHeapsHistoryAndThread) {
  // The generated scan (a building, ground and poles: its front has many edges of the constant
  // stand-by priority) and torus (many equal radii): CGAL orders such ties by address, and with the
  // process heap the scan's three meshes below differed.
  for (const char* shape : {"scan", "torus"}) {
    SCOPED_TRACE(shape);
    const PointSet points = generate_shape(shape, {});
    const TriangleMesh first = reconstruct_surface(points).mesh;
    ASSERT_GT(first.triangles.size(), 1000u);

    const std::vector<void*> kept = fragment_heap();
    const TriangleMesh after_fragmenting = reconstruct_surface(points).mesh;
    for (void* p : kept) std::free(p);
    TriangleMesh on_a_thread;
    std::thread([&] { on_a_thread = reconstruct_surface(points).mesh; }).join();

    EXPECT_EQ(after_fragmenting.triangles, first.triangles);
    EXPECT_EQ(on_a_thread.triangles, first.triangles);
    EXPECT_EQ(after_fragmenting.positions.size(), first.positions.size());
  }
}

TEST(Reconstruct, FlatGridsReconstructLinesAndTooFewPointsAreRefused) {
  PointSet grid, line;
  for (int i = 0; i < 400; ++i) {
    grid.positions.push_back({float(i % 20), float(i / 20), 0.0f});
    line.positions.push_back({float(i), 2.0f * float(i), 0.0f});
  }
  EXPECT_EQ(reconstruct_surface(grid).mesh.triangles.size(), 2u * 19u * 19u);
  EXPECT_THROW(reconstruct_surface(line), std::invalid_argument);
  line.positions.resize(3);
  EXPECT_THROW(reconstruct_surface(line), std::invalid_argument);
}

// The addresses handed out in a scope, as offsets from its first block.
std::vector<std::ptrdiff_t> scope_layout() {
  std::vector<std::ptrdiff_t> offsets;  // the result: on the process heap
  DeterministicHeap heap(std::size_t{64} << 20);
  std::vector<std::unique_ptr<int[]>> blocks;
  blocks.reserve(64);
  const char* origin = reinterpret_cast<const char*>(blocks.data());
  for (int i = 0; i < 64; ++i) {
    blocks.emplace_back(new int[std::size_t(1 + i * 13 % 300)]);
    if (i % 3 == 0) blocks[std::size_t(i / 2)].reset();  // frees inside the scope are reused
  }
  DeterministicHeap::Pause outside;  // the result's growth goes to the process heap
  for (const auto& b : blocks)
    if (b) offsets.push_back(reinterpret_cast<const char*>(b.get()) - origin);
  return offsets;
}

TEST(DeterministicHeap, SameLayoutWhateverCameBefore) {
  const std::vector<std::ptrdiff_t> first = scope_layout();
  const std::vector<void*> kept = fragment_heap();
  EXPECT_EQ(scope_layout(), first);
  std::vector<std::ptrdiff_t> on_a_thread;
  std::thread([&] { on_a_thread = scope_layout(); }).join();
  EXPECT_EQ(on_a_thread, first);
  for (void* p : kept) std::free(p);
}

TEST(DeterministicHeap, OverAlignedBlocksAndNoNesting) {
  DeterministicHeap heap(std::size_t{64} << 20);
  struct alignas(64) Wide { char c[100]; };
  std::unique_ptr<Wide> w(new Wide);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(w.get()) % 64, 0u);
  EXPECT_THROW(DeterministicHeap nested(std::size_t{64} << 20), std::logic_error);
}

TEST(DeterministicHeap, AnAllocationPastTheReserveThrowsBadAlloc) {
  DeterministicHeap heap(std::size_t{1} << 20);
  EXPECT_EQ(heap.reserve_bytes(), std::size_t{1} << 20);
  EXPECT_THROW(std::vector<char>(std::size_t{2} << 20), std::bad_alloc);
  std::vector<char> fits(std::size_t{256} << 10);  // and the region still serves what fits
  EXPECT_EQ(fits.size(), std::size_t{256} << 10);
}

}  // namespace
}  // namespace qf
