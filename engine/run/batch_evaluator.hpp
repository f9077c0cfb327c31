#pragma once
// The one way to run runs (as pagmo2's `bfe` fronts `thread_bfe`): a batch
// of resolved tuples in, their results out, result i in slot i. The checks
// are made once here; an implementation only runs. Every implementation
// gives each run's result as a pure function of its tuple (bit-identical
// whatever the implementation, thread count or SIMD width; wall_time aside).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "engine/rows/run_row.hpp"
#include "engine/run/progress.hpp"

namespace chaosweep {

// What a caller watches or steers while a batch runs (all optional).
struct BatchObserver {
  ProgressCounters* progress = nullptr;  // done and failed (status not ok) bumped as runs finish
  // Once set, no new run starts; the runs in flight finish, so the runs done
  // are a prefix of the batch.
  const std::atomic<bool>* stop = nullptr;
  // finished[i] becomes 1 (release) once out[i] is final, so another thread
  // may take finished results while the batch goes on (size: in.size()).
  std::atomic<std::uint8_t>* finished = nullptr;
};

class BatchEvaluator {
 public:
  virtual ~BatchEvaluator() = default;
  // out[i] = the result of in[i] for i below the returned count: in.size(),
  // or fewer (a prefix) when observer.stop was set. A failing run is a
  // result (its status and message), never an exception. Throws
  // std::invalid_argument when the spans differ in size or a tuple has no
  // environment.
  std::size_t evaluate(std::span<const RunTuple> in, std::span<RunResult> out,
                       const BatchObserver& observer = {}) const;
  // One run (the batch of one).
  RunResult evaluate(const RunTuple& tuple) const;
  // body(i) for every i in [0, n), on the evaluator's threads when it has
  // them (here: in order on this thread): the work that goes with a batch
  // (resolving its tuples, encoding its rows), so that it scales with the
  // runs and --threads bounds it too.
  virtual void parallel(std::size_t n, const std::function<void(std::size_t)>& body) const;

 private:
  virtual std::size_t run(std::span<const RunTuple> in, std::span<RunResult> out,
                          const BatchObserver& observer) const = 0;
};

}  // namespace chaosweep
