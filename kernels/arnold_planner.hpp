#pragma once
// The Arnold-flow planner, scalar reference (seed 000, `original` variant).
#include "coverage_grid.hpp"
#include "environment.hpp"
#include "run_params.hpp"

namespace chaosweep {

// Runs until coverage reaches p.dc or a budget ends the run; fills status,
// coverage_time, steps, t_end, dt_halvings and final position of r.
// Expects validated parameters and r.t_opt set.
void run_arnold(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r);

}  // namespace chaosweep
