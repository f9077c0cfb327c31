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
  // body(i) for every i in [0, n) on this evaluator's threads: work that
  // goes with a batch's rows (e.g. encoding them, H5RunWriter::append), so
  // --threads bounds it too.
  void parallel(std::size_t n, const std::function<void(std::size_t)>& body) const;

 private:
  std::size_t run(std::span<const RunTuple> in, std::span<RunResult> out, const BatchObserver& observer) const override;
  struct Arena;  // the TBB arena, kept out of this header
  std::unique_ptr<Arena> arena_;
  SimdTarget target_;
};

}  // namespace chaosweep
