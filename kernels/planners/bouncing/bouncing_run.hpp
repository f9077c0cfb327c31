#pragma once
// Seed 002's bouncing robot in the common coverage model (planner =
// bouncing): a minimalist robot with a contact sensor drives straight and,
// at each bump, turns by the angle of a policy drawn from the mixture alpha
// (the output of bouncing_paper::best_mixture), so its coverage time compares with
// the chaotic planners' on the same map.
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

// Why p cannot run as a bouncing run (no policy with positive weight), or empty.
std::string validate_bouncing(const RunParams& p);

// Fills r: coverage_time (ok) or timeout at the budget, steps (moves),
// reflections (bumps), t_end, final position. Deterministic given p.seed.
void run_bouncing(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace);

}  // namespace chaosweep
