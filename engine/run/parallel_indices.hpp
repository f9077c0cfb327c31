#pragma once
// body(i) for every i in [0, n) on `arena`'s threads, returning when all
// have finished; the first exception a body throws is rethrown here. The one
// place the engine hands work to oneTBB.
//
// Under ThreadSanitizer the same contract runs on std::threads instead:
// Debian's libtbb is not built with ThreadSanitizer, so it cannot see TBB's
// hand-overs, and silencing the reports they cause needs a suppression that
// matches the TBB frames under every parallel body, which hides real races
// in chaosweep's own code too (tests/tsan/tsan_canary.cpp shows TSan now
// reports one). pthread_create/join are intercepted, so TSan sees every
// hand-over here and tests/tsan.supp needs no TBB entry.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__SANITIZE_THREAD__)
#define CHAOSWEEP_PARALLEL_ON_STD_THREADS 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define CHAOSWEEP_PARALLEL_ON_STD_THREADS 1
#endif
#endif

namespace chaosweep {

template <class Body>
void parallel_indices(tbb::task_arena& arena, std::size_t n, const Body& body) {
#if defined(CHAOSWEEP_PARALLEL_ON_STD_THREADS)
  const std::size_t threads = std::min<std::size_t>(std::size_t(std::max(1, arena.max_concurrency())), n);
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < n;) {
      try {
        body(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next.store(n);  // as TBB cancels the rest
      }
    }
  };
  std::vector<std::thread> helpers;
  for (std::size_t t = 1; t < threads; ++t) helpers.emplace_back(work);
  work();
  for (std::thread& t : helpers) t.join();
  if (failure) std::rethrow_exception(failure);
#else
  arena.execute([&] { tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) { body(i); }); });
#endif
}

// The same on a new arena of `threads` threads (0: all cores).
template <class Body>
void parallel_indices(int threads, std::size_t n, const Body& body) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  parallel_indices(arena, n, body);
}

}  // namespace chaosweep
