#pragma once
// Seed 003's planner in the common coverage model (planner = contraction):
// the path the kernel of contraction.hpp lays in the workplace (one mapped
// trajectory, the complete-coverage loop, or the mirror-mapping baseline) is
// walked at speed v over the common grid, so its coverage time compares with
// the other planners' on the same map.
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

// Why (p, env) cannot run as a contraction run (a workplace with obstacles),
// or empty; validate_run has checked the start lies in the workplace.
std::string validate_contraction(const RunParams& p, const Environment& env);

// Fills r: final_coverage after the whole path, coverage_time when it first
// reached p.dc (status ok; else timeout), steps (RK2 steps laid), segments
// (loop sections), reflections (mirror), t_end, final position.
void run_contraction(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace);

}  // namespace chaosweep
