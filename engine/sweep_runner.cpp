#include "sweep_runner.hpp"

#include <algorithm>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "lane_driver.hpp"

namespace chaosweep {

void preload_environments(const SweepSpec& spec, EnvironmentCache& cache) {
  for (std::int64_t i = 0; i < spec.size(); ++i) {
    const RunSpec r = spec.run(i);
    cache.get(r.env, r.params.size_x, r.params.size_y);
  }
}

namespace {

// Big enough for the lanes to refill many times per task, small enough that
// every thread gets several tasks to steal.
std::int64_t chunk_for(const SweepOptions& opt, std::int64_t n, int threads) {
  if (opt.chunk_size > 0) return opt.chunk_size;
  const std::int64_t lanes = lane_count(opt.target);
  return std::clamp<std::int64_t>(n / (8 * std::max(threads, 1)), lanes, 16 * lanes);
}

// Runs rows[first, first + n): a pure function of the tuples in each slot.
void run_chunk(std::vector<RunRow>& rows, std::int64_t first, std::int64_t n, const SweepOptions& opt) {
  std::vector<BatchItem> items(static_cast<std::size_t>(n));
  std::vector<RunResult> results(static_cast<std::size_t>(n));
  for (std::int64_t k = 0; k < n; ++k) {
    const RunTuple& t = rows[std::size_t(first + k)].tuple;
    items[std::size_t(k)] = {&t.params, t.env.get()};
  }
  run_batch(items.data(), results.data(), std::size_t(n), opt.target);
  std::int64_t failed = 0;
  for (std::int64_t k = 0; k < n; ++k) {
    failed += results[std::size_t(k)].status != Status::ok;
    rows[std::size_t(first + k)].result = std::move(results[std::size_t(k)]);
  }
  if (opt.progress) {
    opt.progress->done += n;
    opt.progress->failed += failed;
  }
}

void run_rows(std::vector<RunRow>& rows, const SweepOptions& opt, tbb::task_arena& arena) {
  const auto n = std::int64_t(rows.size());
  const std::int64_t chunk = chunk_for(opt, n, arena.max_concurrency());
  const std::int64_t chunks = (n + chunk - 1) / chunk;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, chunks, 1), [&](const tbb::blocked_range<std::int64_t>& r) {
      for (std::int64_t c = r.begin(); c != r.end(); ++c) {
        const std::int64_t first = c * chunk;
        // run_batch records every failing run itself; this only guards
        // against a failure of the chunk's own bookkeeping (e.g. memory).
        try {
          run_chunk(rows, first, std::min(chunk, n - first), opt);
        } catch (const std::exception& e) {
          for (std::int64_t k = first; k < std::min(first + chunk, n); ++k) {
            rows[std::size_t(k)].result = RunResult{};
            rows[std::size_t(k)].result.status = Status::error;
            rows[std::size_t(k)].result.message = e.what();
          }
        }
      }
    });
  });
}

}  // namespace

std::vector<RunRow> run_tuples(const std::vector<RunTuple>& tuples, const SweepOptions& opt) {
  tbb::task_arena arena(opt.threads > 0 ? opt.threads : tbb::task_arena::automatic);
  std::vector<RunRow> rows;
  for (const RunTuple& t : tuples) rows.push_back({t, {}});
  run_rows(rows, opt, arena);
  return rows;
}

void run_sweep(const SweepSpec& spec, const SweepOptions& opt, const RowSink& sink) {
  EnvironmentCache cache;
  preload_environments(spec, cache);
  const std::int64_t total = spec.size();
  tbb::task_arena arena(opt.threads > 0 ? opt.threads : tbb::task_arena::automatic);
  std::vector<RunRow> rows;
  for (std::int64_t first = 0; first < total; first += opt.batch_size) {
    const std::int64_t n = std::min(opt.batch_size, total - first);
    rows.assign(std::size_t(n), RunRow{});
    for (std::int64_t k = 0; k < n; ++k) rows[std::size_t(k)].tuple = resolve_run(first + k, spec.run(first + k), cache);
    run_rows(rows, opt, arena);
    sink(rows);
  }
}

std::vector<RunRow> run_sweep_rows(const SweepSpec& spec, const SweepOptions& opt) {
  std::vector<RunRow> all;
  run_sweep(spec, opt, [&](const std::vector<RunRow>& batch) { all.insert(all.end(), batch.begin(), batch.end()); });
  return all;
}

}  // namespace chaosweep
