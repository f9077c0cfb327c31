#pragma once
// Streams the runs of a spec through a batch evaluator
// (engine/run/batch_evaluator.hpp) and hands result rows back in run_id
// order, a batch at a time. Results land in their runs' slots, so the output
// never depends on the evaluator, its thread count or kernel width, or on
// the batch size.
#include <cstdint>
#include <functional>
#include <vector>

#include "engine/run/batch_evaluator.hpp"
#include "engine/run/progress.hpp"
#include "engine/spec/environment_loader.hpp"
#include "engine/spec/run_tuple.hpp"
#include "engine/spec/shard.hpp"
#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

struct SweepOptions {
  std::int64_t batch_size = 4096;  // runs scheduled at once: at most this many rows per sink call
  // Also hand the finished runs (a run_id prefix) to the sink while a batch
  // runs, once this many seconds passed since the last hand-over (0: only
  // at the end of each batch).
  double flush_seconds = 10;
  ProgressCounters* progress = nullptr;     // bumped as runs complete
  int shard_index = 0, shard_count = 1;     // this process runs run_ids i with i % count == index
  std::int64_t skip = 0;                    // runs of the shard already done (resume)
  const std::atomic<bool>* stop = nullptr;  // set by SIGINT/SIGTERM: finish runs in flight, return
};

// A sink takes a piece of rows on the sweep's thread (it may use the
// evaluator's threads meanwhile) and returns their write (or nothing): the
// part that must run alone, which run_sweep runs on a thread of its own, in
// order, while the next batch runs (WriteBehind).
using RowWrite = std::function<void()>;
using RowSink = std::function<RowWrite(const std::vector<RunRow>&)>;

// Loads every environment the spec names; throws on the first bad one, so a
// sweep with bad input fails before any run starts.
void preload_environments(const SweepSpec& spec, EnvironmentCache& cache);

// Runs the shard's runs after the first opt.skip on `evaluator`, calling sink with
// consecutive pieces in run_id order (each batch in one piece, or in several
// when opt.flush_seconds passes first; the sink may be called from a thread
// of the runner, never from two at once); returns, once every write the
// sink returned has finished, how many runs it handed over (fewer than the
// shard's when stopped). An exception from the sink or a write stops the
// runs and is rethrown. `preloaded`: a cache the caller has
// already filled with preload_environments (saves a pass over the spec).
std::int64_t run_sweep(const SweepSpec& spec, const BatchEvaluator& evaluator, const SweepOptions& opt,
                       const RowSink& sink, EnvironmentCache* preloaded = nullptr);

}  // namespace chaosweep
