#pragma once
// Fans the runs of a spec out over oneTBB and hands result rows back in
// run_id order, a batch at a time. Only parallelises: each worker drives its
// own lanes (kernels/lane_driver.hpp) from a shared queue of the batch's
// runs; results land in their runs' slots, so the output never depends on
// the thread count, on which lane ran what, or on the kernel width.
#include <cstdint>
#include <functional>
#include <vector>

#include "engine/spec/environment_loader.hpp"
#include "engine/spec/shard.hpp"
#include "engine/run/progress.hpp"
#include "engine/spec/run_tuple.hpp"
#include "kernels/lanes/simd_target.hpp"
#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

struct SweepOptions {
  int threads = 0;                    // 0: all cores
  std::int64_t batch_size = 4096;     // runs scheduled at once: at most this many rows per sink call
  // Also hand the finished runs (a run_id prefix) to the sink while a batch
  // runs, once this many seconds passed since the last hand-over (0: only
  // at the end of each batch).
  double flush_seconds = 10;
  SimdTarget target = best_simd_target();
  ProgressCounters* progress = nullptr;  // bumped as runs complete
  int shard_index = 0, shard_count = 1;  // this process runs run_ids i with i % count == index
  std::int64_t skip = 0;                 // runs of the shard already done (resume)
  const std::atomic<bool>* stop = nullptr;  // set by SIGINT/SIGTERM: finish runs in flight, return
};


using RowSink = std::function<void(const std::vector<RunRow>&)>;

// Loads every environment the spec names; throws on the first bad one, so a
// sweep with bad input fails before any run starts.
void preload_environments(const SweepSpec& spec, EnvironmentCache& cache);

// Runs the shard's runs after the first opt.skip, calling sink with
// consecutive pieces in run_id order (each batch in one piece, or in several
// when opt.flush_seconds passes first; the sink may be called from a thread
// of the runner, never from two at once); returns how many runs it handed
// over (fewer than the shard's when stopped). An exception from the sink
// stops the runs and is rethrown. `preloaded`: a cache the caller has
// already filled with preload_environments (saves a pass over the spec).
std::int64_t run_sweep(const SweepSpec& spec, const SweepOptions& opt, const RowSink& sink,
                       EnvironmentCache* preloaded = nullptr);

// Runs already-resolved tuples (results in tuple order) on `opt`'s arena size.
std::vector<RunRow> run_tuples(const std::vector<RunTuple>& tuples, const SweepOptions& opt);

// All rows at once (tests, small sweeps).
std::vector<RunRow> run_sweep_rows(const SweepSpec& spec, const SweepOptions& opt);

}  // namespace chaosweep
