#include "engine/run/serial_batch_evaluator.hpp"

#include <chrono>
#include <exception>

#include "kernels/planners/planner.hpp"

namespace chaosweep {

namespace {

// Runs the kernel, timing it; never throws (an exception becomes status error).
RunResult run_one(const RunTuple& t, TraceSink* trace) {
  RunResult result;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    result = run_planner(t.params, *t.env, trace);
  } catch (const std::exception& e) {
    result = RunResult{};
    result.status = Status::error;
    result.message = e.what();
  } catch (...) {
    result = RunResult{};
    result.status = Status::error;
    result.message = "unknown exception";
  }
  result.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace

std::size_t SerialBatchEvaluator::run(std::span<const RunTuple> in, std::span<RunResult> out,
                                      const BatchObserver& observer) const {
  std::size_t k = 0;
  for (; k < in.size(); ++k) {
    if (observer.stop && observer.stop->load()) break;
    out[k] = run_one(in[k], trace_);
    if (observer.progress) {
      observer.progress->done += 1;
      if (out[k].status != Status::ok) observer.progress->failed += 1;
    }
    if (observer.finished) observer.finished[k].store(1, std::memory_order_release);
  }
  return k;
}

}  // namespace chaosweep
