#pragma once
// The scalar reference batch evaluator: one run after another on the calling
// thread, each through the planner's own scalar path (no lanes), optionally
// traced. What `run` uses, and what the lanes are tested against.
#include "engine/run/batch_evaluator.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

class SerialBatchEvaluator final : public BatchEvaluator {
 public:
  // trace: receives every evaluated run's trajectory (nullptr: none).
  explicit SerialBatchEvaluator(TraceSink* trace = nullptr) : trace_(trace) {}

 private:
  std::size_t run(std::span<const RunTuple> in, std::span<RunResult> out, const BatchObserver& observer) const override;
  TraceSink* trace_;
};

}  // namespace chaosweep
