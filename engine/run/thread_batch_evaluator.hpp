#pragma once
// The batch evaluator of sweeps: the runs fanned out over oneTBB workers,
// each driving its own SIMD lanes (kernels/lanes/lane_driver.hpp) from one
// shared queue, so lanes idle only at the end of a batch.
#include <cstddef>
#include <functional>
#include <memory>

#include "engine/run/batch_evaluator.hpp"
#include "kernels/lanes/simd_target.hpp"

namespace chaosweep {

class ThreadBatchEvaluator final : public BatchEvaluator {
 public:
  // threads 0: all cores.
  explicit ThreadBatchEvaluator(int threads = 0, SimdTarget target = best_simd_target());
  ~ThreadBatchEvaluator() override;
  ThreadBatchEvaluator(const ThreadBatchEvaluator&) = delete;
  ThreadBatchEvaluator& operator=(const ThreadBatchEvaluator&) = delete;
  SimdTarget target() const { return target_; }
  // On this evaluator's threads (its arena).
  void parallel(std::size_t n, const std::function<void(std::size_t)>& body) const override;

 private:
  std::size_t run(std::span<const RunTuple> in, std::span<RunResult> out, const BatchObserver& observer) const override;
  struct Arena;  // the TBB arena, kept out of this header
  std::unique_ptr<Arena> arena_;
  SimdTarget target_;
};

}  // namespace chaosweep
