// A deliberate data race inside parallel_indices' bodies: every body adds to
// one plain int. Registered only in a ThreadSanitizer build, where the test
// passes only if TSan reports the race in tsan_canary_bump, so the TSan
// suite's suppressions (tests/tsan.supp) cannot silently hide races in
// chaosweep's parallel code, as a match on TBB's frames once did.
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <thread>

#include "engine/run/parallel_indices.hpp"

static int shared_sum = 0;

__attribute__((noinline)) void tsan_canary_bump(std::size_t i) { shared_sum += int(i); }

int main() {
  tbb::task_arena arena(2);
  // Each body lingers, so that both threads take bodies of the same call
  // (sleeping orders nothing for TSan).
  for (int round = 0; round < 10; ++round)
    chaosweep::parallel_indices(arena, 16, [](std::size_t i) {
      tsan_canary_bump(i);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    });
  std::printf("sum %d\n", shared_sum);
  return 0;
}
