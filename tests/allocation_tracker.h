// Measures the largest single allocation a piece of code makes, by replacing the global
// operator new and delete. Include it in exactly one source file of a test executable.
#ifndef MESHVID_TESTS_ALLOCATION_TRACKER_H_
#define MESHVID_TESTS_ALLOCATION_TRACKER_H_

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace meshvid::testing::allocations {
inline std::atomic<bool> tracking{false};
inline std::atomic<std::size_t> largest{0};
}  // namespace meshvid::testing::allocations

void* operator new(std::size_t size) {
  namespace a = meshvid::testing::allocations;
  if (a::tracking.load(std::memory_order_relaxed)) {
    std::size_t seen = a::largest.load();
    while (size > seen && !a::largest.compare_exchange_weak(seen, size)) {
    }
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// Not inlined, so the compiler does not see free() meet memory from new (a false warning).
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace meshvid::testing {

/// Tracks the largest allocation made from its construction until Stop() or its end.
class AllocationTracker {
 public:
  AllocationTracker() {
    allocations::largest = 0;
    allocations::tracking = true;
  }
  ~AllocationTracker() { Stop(); }
  AllocationTracker(const AllocationTracker&) = delete;
  AllocationTracker& operator=(const AllocationTracker&) = delete;
  void Stop() { allocations::tracking = false; }
  std::size_t largest() const { return allocations::largest.load(); }
};

}  // namespace meshvid::testing

#endif  // MESHVID_TESTS_ALLOCATION_TRACKER_H_
