#pragma once
// body(i) for every i in [0, n) on `arena`'s threads, returning when all
// have finished. The one place the engine hands work to oneTBB, so the two
// atomics below serve every caller: Debian's libtbb is not built with
// ThreadSanitizer, which then cannot see that the caller's writes precede
// the workers' reads and that the workers finished before the caller reads
// their results (tests/tsan.supp). They cost two atomic operations per call.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <atomic>
#include <cstddef>

namespace chaosweep {

template <class Body>
void parallel_indices(tbb::task_arena& arena, std::size_t n, const Body& body) {
  std::atomic<int> started{0}, finished{0};
  started.store(1, std::memory_order_release);
  arena.execute([&] {
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
      (void)started.load(std::memory_order_acquire);
      body(i);
      finished.fetch_add(1, std::memory_order_release);
    });
  });
  (void)finished.load(std::memory_order_acquire);
}

// The same on a new arena of `threads` threads (0: all cores).
template <class Body>
void parallel_indices(int threads, std::size_t n, const Body& body) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  parallel_indices(arena, n, body);
}

}  // namespace chaosweep
