#pragma once
// How long a sweep will take, from calibration runs drawn across its spec
// (`chaosweep plan --estimate`): a stratified sample of run_ids (one from each
// of K equal slices of 0..N-1, at a seeded random place), run to completion
// on the evaluator the sweep would use. The wall time is N/K times the
// sample's, and its uncertainty the sampling error of the runs' work
// (integration steps and transit points), which is what their times differ by.
#include <cstdint>

#include "engine/run/batch_evaluator.hpp"
#include "engine/spec/environment_loader.hpp"
#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

struct WallTimeEstimate {
  std::int64_t runs_drawn = 0;  // K (at most the spec's runs)
  double sample_seconds = 0;    // wall time of the calibration runs
  double seconds = 0;           // the estimate for the whole spec
  double low = 0, high = 0;     // ~95% interval (mean work +- 2 standard errors)
};

// The stratified run_ids: slice k of n equal slices of [0, runs), each at a
// place drawn from `seed` (every run_id once at most; all when n >= runs).
std::vector<std::int64_t> calibration_run_ids(std::int64_t runs, std::int64_t n, std::uint64_t seed);

// The estimate from the sample's wall time and each drawn run's work.
WallTimeEstimate extrapolate_wall_time(std::int64_t runs, double sample_seconds, const std::vector<double>& work);

WallTimeEstimate estimate_wall_time(const SweepSpec& spec, EnvironmentCache& cache, const BatchEvaluator& evaluator,
                                    std::int64_t calibration_runs, std::uint64_t seed = 1);

}  // namespace chaosweep
