#pragma once
// The naive scalar baseline `chaosweep bench` compares the kernels with: the
// original Arnold planner written plainly, with glibc sin/cos and no lanes.
// Kept only for benchmarking; its results are not the engine's.
#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"

namespace chaosweep {

// Runs p (fixed-step RK4, mirror boundary, no obstacles) and returns its steps.
long naive_original_arnold(const RunParams& p, const Environment& env);

}  // namespace chaosweep
