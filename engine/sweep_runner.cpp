#include "sweep_runner.hpp"

#include <algorithm>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace chaosweep {

void preload_environments(const SweepSpec& spec, EnvironmentCache& cache) {
  for (std::int64_t i = 0; i < spec.size(); ++i) {
    const RunSpec r = spec.run(i);
    cache.get(r.env, r.params.size_x, r.params.size_y);
  }
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
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, n, 1),
                        [&](const tbb::blocked_range<std::int64_t>& r) {
                          for (std::int64_t k = r.begin(); k != r.end(); ++k)
                            rows[std::size_t(k)] = evaluate(resolve_run(first + k, spec.run(first + k), cache));
                        });
    });
    sink(rows);
  }
}

std::vector<RunRow> run_sweep_rows(const SweepSpec& spec, const SweepOptions& opt) {
  std::vector<RunRow> all;
  run_sweep(spec, opt, [&](const std::vector<RunRow>& batch) {
    all.insert(all.end(), batch.begin(), batch.end());
  });
  return all;
}

}  // namespace chaosweep
