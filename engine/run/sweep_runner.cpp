#include "engine/run/sweep_runner.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include <tbb/task_arena.h>

#include "kernels/lanes/lane_driver.hpp"
#include "engine/run/parallel_indices.hpp"

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

// Timed hand-over (SweepOptions::flush_seconds): the sink and when it last
// got rows.
struct TimedSink {
  const RowSink& sink;
  double seconds;
  clock_type::time_point last = clock_type::now();
  bool due() const { return std::chrono::duration<double>(clock_type::now() - last).count() >= seconds; }
};

// Moves rows [from, to) (tuples and their results) into one piece for the sink.
std::vector<RunRow> take_rows(std::vector<RunRow>& rows, std::vector<RunResult>& results, std::size_t from,
                              std::size_t to) {
  std::vector<RunRow> piece;
  piece.reserve(to - from);
  for (std::size_t k = from; k < to; ++k) {
    rows[k].result = std::move(results[k]);
    piece.push_back(std::move(rows[k]));
  }
  return piece;
}

// Runs rows[*] (tuples set): every worker of the arena drives its own lanes,
// pulling the next run from one shared queue as soon as a lane frees up, so
// lanes idle only at the end of the batch. Each result is a pure function of
// its tuple and lands in its row's slot. With `timed`, a watcher thread hands
// the finished prefix of the batch to its sink whenever it is due (and
// relays opt.stop to the lanes); `handed` says how many rows it took. The
// rows left, up to the returned count, are rows [handed, count).
std::size_t run_rows(std::vector<RunRow>& rows, const SweepOptions& opt, tbb::task_arena& arena,
                     TimedSink* timed, std::size_t& handed) {
  const std::size_t n = rows.size();
  std::vector<BatchItem> items(n);
  std::vector<RunResult> results(n);
  for (std::size_t k = 0; k < n; ++k) {
    items[k] = {&rows[k].tuple.params, rows[k].tuple.env.get()};
    results[k].status = Status::error;  // stays so only if a worker itself fails
    results[k].message = "not run: its worker failed";
  }
  std::unique_ptr<std::atomic<std::uint8_t>[]> finished;
  std::atomic<bool> halt{false};
  RunQueue queue{items.data(), results.data(), n};
  queue.stop = opt.stop;
  if (timed) {
    finished = std::make_unique<std::atomic<std::uint8_t>[]>(n);  // zeroed
    queue.finished = finished.get();
    queue.stop = &halt;
  }
  if (opt.progress) {
    queue.done = &opt.progress->done;
    queue.not_ok = &opt.progress->failed;
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
          timed->sink(take_rows(rows, results, handed, p));
          timed->last = clock_type::now();
        } catch (...) {
          sink_failed = std::current_exception();
          halt.store(true);  // no new runs: the sweep stops
        }
        handed = p;
      }
    });
  const int workers = std::max(1, arena.max_concurrency());
  parallel_indices(arena, std::size_t(workers), [&](std::size_t) {
    // A failure of a worker's own bookkeeping (e.g. memory) leaves its
    // in-flight runs marked error; the other workers go on.
    try {
      run_queue(queue, opt.target);
    } catch (const std::exception&) {
    }
  });
  if (timed) {
    {
      std::lock_guard<std::mutex> lock(m);
      batch_done = true;
    }
    cv.notify_one();
    watcher.join();
    if (sink_failed) std::rethrow_exception(sink_failed);
  }
  for (std::size_t k = handed; k < n; ++k) rows[k].result = std::move(results[k]);
  return std::min(queue.next.load(), n);  // all claimed runs have finished
}

}  // namespace

std::vector<RunRow> run_tuples(const std::vector<RunTuple>& tuples, const SweepOptions& opt) {
  tbb::task_arena arena(opt.threads > 0 ? opt.threads : tbb::task_arena::automatic);
  std::vector<RunRow> all, rows;
  for (std::size_t first = 0; first < tuples.size(); first += std::size_t(opt.batch_size)) {
    rows.clear();
    for (std::size_t k = first; k < std::min(tuples.size(), first + std::size_t(opt.batch_size)); ++k)
      rows.push_back({tuples[k], {}});
    std::size_t handed = 0;
    run_rows(rows, opt, arena, nullptr, handed);
    all.insert(all.end(), rows.begin(), rows.end());
  }
  return all;
}

std::int64_t run_sweep(const SweepSpec& spec, const SweepOptions& opt, const RowSink& sink,
                       EnvironmentCache* preloaded) {
  EnvironmentCache own;
  if (!preloaded) preload_environments(spec, own);
  EnvironmentCache& cache = preloaded ? *preloaded : own;
  const std::int64_t total = shard_size(spec.size(), opt.shard_index, opt.shard_count);
  tbb::task_arena arena(opt.threads > 0 ? opt.threads : tbb::task_arena::automatic);
  std::vector<RunRow> rows;
  std::int64_t handed = 0;
  TimedSink timed{sink, opt.flush_seconds};
  for (std::int64_t first = opt.skip; first < total; first += opt.batch_size) {
    if (opt.stop && opt.stop->load()) break;
    const std::int64_t n = std::min(opt.batch_size, total - first);
    rows.assign(std::size_t(n), RunRow{});
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t id = shard_run_id(first + k, opt.shard_index, opt.shard_count);
      rows[std::size_t(k)].tuple = resolve_run(id, spec.run(id), cache);
    }
    std::size_t early = 0;  // rows the watcher handed over already
    const std::size_t done = run_rows(rows, opt, arena, opt.flush_seconds > 0 ? &timed : nullptr, early);
    rows.resize(done);
    rows.erase(rows.begin(), rows.begin() + std::ptrdiff_t(std::min(early, done)));
    if (!rows.empty()) {
      sink(rows);
      timed.last = std::chrono::steady_clock::now();
    }
    handed += std::int64_t(done);
    if (std::int64_t(done) < n) break;  // stopped
  }
  return handed;
}

std::vector<RunRow> run_sweep_rows(const SweepSpec& spec, const SweepOptions& opt) {
  std::vector<RunRow> all;
  run_sweep(spec, opt, [&](const std::vector<RunRow>& batch) { all.insert(all.end(), batch.begin(), batch.end()); });
  return all;
}

}  // namespace chaosweep
