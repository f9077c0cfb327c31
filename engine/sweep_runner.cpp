#include "sweep_runner.hpp"

#include <algorithm>
#include <tbb/task_arena.h>

#include "lane_driver.hpp"
#include "parallel_indices.hpp"

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

// Runs rows[*] (tuples set): every worker of the arena drives its own lanes,
// pulling the next run from one shared queue as soon as a lane frees up, so
// lanes idle only at the end of the batch. Each result is a pure function of
// its tuple and lands in its row's slot.
std::size_t run_rows(std::vector<RunRow>& rows, const SweepOptions& opt, tbb::task_arena& arena) {
  const std::size_t n = rows.size();
  std::vector<BatchItem> items(n);
  std::vector<RunResult> results(n);
  for (std::size_t k = 0; k < n; ++k) {
    items[k] = {&rows[k].tuple.params, rows[k].tuple.env.get()};
    results[k].status = Status::error;  // stays so only if a worker itself fails
    results[k].message = "not run: its worker failed";
  }
  RunQueue queue{items.data(), results.data(), n};
  queue.stop = opt.stop;
  if (opt.progress) {
    queue.done = &opt.progress->done;
    queue.not_ok = &opt.progress->failed;
  }
  const int workers = std::max(1, arena.max_concurrency());
  parallel_indices(arena, std::size_t(workers), [&](std::size_t) {
    // A failure of a worker's own bookkeeping (e.g. memory) leaves its
    // in-flight runs marked error; the other workers go on.
    try {
      run_queue(queue, opt.target);
    } catch (const std::exception&) {
    }
  });
  for (std::size_t k = 0; k < n; ++k) rows[k].result = std::move(results[k]);
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
    run_rows(rows, opt, arena);
    all.insert(all.end(), rows.begin(), rows.end());
  }
  return all;
}

std::int64_t shard_size(std::int64_t total, int index, int count) {
  return index < total ? (total - index + count - 1) / count : 0;
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
  for (std::int64_t first = opt.skip; first < total; first += opt.batch_size) {
    if (opt.stop && opt.stop->load()) break;
    const std::int64_t n = std::min(opt.batch_size, total - first);
    rows.assign(std::size_t(n), RunRow{});
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t id = shard_run_id(first + k, opt.shard_index, opt.shard_count);
      rows[std::size_t(k)].tuple = resolve_run(id, spec.run(id), cache);
    }
    const std::size_t done = run_rows(rows, opt, arena);
    rows.resize(done);
    if (!rows.empty()) sink(rows);
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
