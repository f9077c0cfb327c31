#pragma once
// All rows of a sweep at once, through the streaming runner (small test sweeps).
#include <vector>

#include "engine/run/sweep_runner.hpp"
#include "engine/run/thread_batch_evaluator.hpp"

namespace chaosweep {

inline std::vector<RunRow> sweep_rows(const SweepSpec& spec, const BatchEvaluator& evaluator,
                                      const SweepOptions& opt = {}) {
  std::vector<RunRow> all;
  run_sweep(spec, evaluator, opt, [&](const std::vector<RunRow>& rows) -> RowWrite {
    all.insert(all.end(), rows.begin(), rows.end());
    return {};
  });
  return all;
}

inline std::vector<RunRow> sweep_rows(const SweepSpec& spec, const SweepOptions& opt = {}) {
  return sweep_rows(spec, ThreadBatchEvaluator(), opt);
}

}  // namespace chaosweep
