#pragma once
// How much work a sweep can take, for `chaosweep plan`: every run to its
// time budget (max_time, or max_pr x T_opt), in integration steps. Only the
// axes that change a run's budget are walked; the others multiply the count,
// so a spec of 1e9 runs over budget-free axes costs one budget, not 1e9.
#include <cstdint>

#include "engine/spec/environment_loader.hpp"
#include "engine/spec/run_tuple.hpp"
#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

struct WorkBound {
  double steps = 0;            // integration steps, at most (estimated when sampled)
  std::int64_t evaluated = 0;  // budgets computed
  bool sampled = false;        // some product had too many budget combinations: estimated from a sample
};

// The steps a run of `p` on a map of `free_area` m^2 may take: its time
// budget over its step.
double run_step_bound(const RunParams& p, double free_area);

// Walks every combination of the budget axes of each product (the spec, or
// each part) when there are at most `max_exact` of them, else averages
// `max_exact` seeded draws of them. Environments come from `cache` (loaded
// on first use; bad ones throw, as in a sweep).
WorkBound bound_work(const SweepSpec& spec, EnvironmentCache& cache, std::int64_t max_exact = 100000);

}  // namespace chaosweep
