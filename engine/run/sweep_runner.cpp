#include "engine/run/sweep_runner.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "engine/run/write_behind.hpp"

namespace chaosweep {

void preload_environments(const SweepSpec& spec, EnvironmentCache& cache) {
  for (const MapVariant& v : spec.environment_variants()) {
    try {
      cache.get(v.run.env, v.run.params.size_x, v.run.params.size_y);
    } catch (const std::exception& e) {
      throw SpecError(v.origin + ": " + e.what());
    }
  }
}

namespace {

using clock_type = std::chrono::steady_clock;

// Timed hand-over (SweepOptions::flush_seconds): the sink, its writes and
// when it last got rows.
struct TimedSink {
  const RowSink& sink;
  WriteBehind& writes;
  double seconds;
  clock_type::time_point last = clock_type::now();
  bool due() const { return std::chrono::duration<double>(clock_type::now() - last).count() >= seconds; }
};

// Moves runs [from, to) (tuples and their results) into `piece` for the
// sink: a vector kept from batch to batch (a fresh one cost the serial
// thread page faults), filled in blocks through `parallel` when given.
// Its rows are overwritten, not cleared first: clearing destroyed and made
// every row again on the sweep's serial thread.
const std::vector<RunRow>& take_rows(std::vector<RunTuple>& tuples, std::vector<RunResult>& results, std::size_t from,
                                     std::size_t to, std::vector<RunRow>& piece,
                                     const BatchEvaluator* parallel = nullptr) {
  piece.resize(to - from);
  constexpr std::size_t block = 256;
  auto move_block = [&](std::size_t b) {
    for (std::size_t k = from + b * block; k < std::min(to, from + (b + 1) * block); ++k) {
      piece[k - from].tuple = std::move(tuples[k]);
      piece[k - from].result = std::move(results[k]);
    }
  };
  const std::size_t blocks = (to - from + block - 1) / block;
  if (parallel) {
    parallel->parallel(blocks, move_block);
  } else {
    for (std::size_t b = 0; b < blocks; ++b) move_block(b);
  }
  return piece;
}

// Runs one batch of tuples on `evaluator`. With `timed`, a watcher thread
// hands the finished prefix of the batch to its sink whenever it is due (and
// relays opt.stop to the evaluator); `handed` says how many runs it took.
// The runs left, up to the returned count, are [handed, count).
std::size_t run_batch_of(std::vector<RunTuple>& tuples, std::vector<RunResult>& results,
                         const BatchEvaluator& evaluator, const SweepOptions& opt, TimedSink* timed,
                         std::size_t& handed) {
  const std::size_t n = tuples.size();
  results.resize(n);  // the evaluator resets each slot it is given
  std::unique_ptr<std::atomic<std::uint8_t>[]> finished;
  std::atomic<bool> halt{false};
  BatchObserver observer;
  observer.progress = opt.progress;
  observer.stop = opt.stop;
  if (timed) {
    finished = std::make_unique<std::atomic<std::uint8_t>[]>(n);  // zeroed
    observer.finished = finished.get();
    observer.stop = &halt;
  }
  handed = 0;
  std::mutex m;
  std::condition_variable cv;
  bool batch_done = false;
  std::exception_ptr sink_failed;
  std::thread watcher;
  if (timed)
    watcher = std::thread([&] {
      std::unique_lock<std::mutex> lock(m);
      while (!cv.wait_for(lock, std::chrono::milliseconds(20), [&] { return batch_done; })) {
        if (opt.stop && opt.stop->load()) halt.store(true);
        if (sink_failed || !timed->due()) continue;
        std::size_t p = handed;
        while (p < n && finished[p].load(std::memory_order_acquire)) ++p;
        if (p == handed) continue;
        try {
          std::vector<RunRow> piece;
          timed->writes.hand_over(timed->sink(take_rows(tuples, results, handed, p, piece)));
          timed->last = clock_type::now();
        } catch (...) {
          sink_failed = std::current_exception();
          halt.store(true);  // no new runs: the sweep stops
        }
        handed = p;
      }
    });
  std::size_t done = 0;
  std::exception_ptr evaluator_failed;
  try {
    done = evaluator.evaluate(tuples, results, observer);
  } catch (...) {
    evaluator_failed = std::current_exception();
  }
  if (timed) {
    {
      std::lock_guard<std::mutex> lock(m);
      batch_done = true;
    }
    cv.notify_one();
    watcher.join();
    if (sink_failed) std::rethrow_exception(sink_failed);
  }
  if (evaluator_failed) std::rethrow_exception(evaluator_failed);
  return done;
}

}  // namespace

std::int64_t run_sweep(const SweepSpec& spec, const BatchEvaluator& evaluator, const SweepOptions& opt,
                       const RowSink& sink, EnvironmentCache* preloaded) {
  EnvironmentCache own;
  if (!preloaded) preload_environments(spec, own);
  EnvironmentCache& cache = preloaded ? *preloaded : own;
  const std::int64_t total = shard_size(spec.size(), opt.shard_index, opt.shard_count);
  std::vector<RunTuple> tuples;
  std::vector<RunResult> results;
  std::vector<RunRow> piece;
  std::int64_t handed = 0;
  WriteBehind writes;
  TimedSink timed{sink, writes, opt.flush_seconds};
  for (std::int64_t first = opt.skip; first < total; first += opt.batch_size) {
    if (opt.stop && opt.stop->load()) break;
    const std::int64_t n = std::min(opt.batch_size, total - first);
    // Tuple k into slot k, in blocks on the evaluator's threads (resized,
    // not reassigned: each slot is overwritten).
    tuples.resize(std::size_t(n));
    constexpr std::int64_t block = 256;
    evaluator.parallel(std::size_t((n + block - 1) / block), [&](std::size_t b) {
      for (std::int64_t k = std::int64_t(b) * block; k < std::min(n, std::int64_t(b + 1) * block); ++k) {
        const std::int64_t id = shard_run_id(first + k, opt.shard_index, opt.shard_count);
        tuples[std::size_t(k)] = resolve_run(id, spec.run(id), cache);
      }
    });
    std::size_t early = 0;  // runs the watcher handed over already
    const std::size_t done =
        run_batch_of(tuples, results, evaluator, opt, opt.flush_seconds > 0 ? &timed : nullptr, early);
    if (early < done) {
      writes.hand_over(sink(take_rows(tuples, results, early, done, piece, &evaluator)));
      timed.last = std::chrono::steady_clock::now();
    }
    handed += std::int64_t(done);
    if (std::int64_t(done) < n) break;  // stopped
  }
  writes.wait();
  return handed;
}

}  // namespace chaosweep
