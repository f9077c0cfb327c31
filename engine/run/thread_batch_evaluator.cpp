#include "engine/run/thread_batch_evaluator.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <vector>

#include "engine/run/parallel_indices.hpp"
#include "kernels/lanes/lane_driver.hpp"

namespace chaosweep {

struct ThreadBatchEvaluator::Arena {
  explicit Arena(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
  tbb::task_arena arena;
  std::atomic<int> batches_running{0};  // run() calls holding the arena's threads
};

ThreadBatchEvaluator::ThreadBatchEvaluator(int threads, SimdTarget target)
    : arena_(std::make_unique<Arena>(threads)), target_(target) {}

ThreadBatchEvaluator::~ThreadBatchEvaluator() = default;

void ThreadBatchEvaluator::parallel(std::size_t n, const std::function<void(std::size_t)>& body) const {
  // While run() holds every thread of the arena for a batch, a caller from
  // outside it (the sweep's timed hand-over of finished rows) would wait
  // until the batch's queue ran dry, so no row reached OUT.partial by time
  // at 2 threads and more: it does the work on its own thread instead.
  if (arena_->batches_running.load(std::memory_order_acquire) > 0) {
    for (std::size_t i = 0; i < n; ++i) body(i);
    return;
  }
  parallel_indices(arena_->arena, n, body);
}

std::size_t ThreadBatchEvaluator::run(std::span<const RunTuple> in, std::span<RunResult> out,
                                      const BatchObserver& observer) const {
  const std::size_t n = in.size();
  std::vector<BatchItem> items(n);
  tbb::task_arena& arena = arena_->arena;
  // In blocks on the arena's threads: on the caller's alone, the slots'
  // reset (and the first batch's page faults) kept the other threads idle.
  constexpr std::size_t block = 256;
  parallel_indices(arena, (n + block - 1) / block, [&](std::size_t b) {
    for (std::size_t k = b * block; k < std::min(n, (b + 1) * block); ++k) {
      items[k] = {&in[k].params, in[k].env.get()};
      out[k] = RunResult{};
      out[k].status = Status::error;  // stays so only if a worker itself fails
      out[k].message = "not run: its worker failed";
    }
  });
  RunQueue queue{items.data(), out.data(), n};
  queue.stop = observer.stop;
  queue.finished = observer.finished;
  if (observer.progress) {
    queue.done = &observer.progress->done;
    queue.not_ok = &observer.progress->failed;
  }
  const int workers = std::max(1, arena.max_concurrency());
  arena_->batches_running.fetch_add(1, std::memory_order_acq_rel);
  struct Leave {
    std::atomic<int>& n;
    ~Leave() { n.fetch_sub(1, std::memory_order_acq_rel); }
  } leave{arena_->batches_running};
  parallel_indices(arena, std::size_t(workers), [&](std::size_t) {
    // A failure of a worker's own bookkeeping (e.g. memory) leaves its
    // in-flight runs marked error; the other workers go on.
    try {
      run_queue(queue, target_);
    } catch (const std::exception&) {
    }
  });
  return std::min(queue.next.load(), n);  // all claimed runs have finished
}

}  // namespace chaosweep
