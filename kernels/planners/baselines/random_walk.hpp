#pragma once
// The random walk (planner = random_walk), the "random path planner" chaotic
// planners are compared with (docs/spec.md §7): moves of length `step` at
// speed v, each in a fresh heading drawn uniformly in [0, 2 pi) from `seed`;
// a heading whose move would leave the free space is drawn again.
#include <string>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

// Headings drawn in a row for one move before the walk counts as boxed in
// (stuck): even in a corner a quarter of the headings are free for a move
// shorter than the free space around it, so a free walk gets here with
// probability below 0.75^max_redraws.
inline constexpr int max_redraws = 1000;

// Why p cannot run as a random walk on env (a step no shorter than the
// map), or empty.
std::string validate_random_walk(const RunParams& p, const Environment& env);

// Fills r: status (ok, timeout, stuck), coverage_time, steps (moves),
// reflections (headings drawn again), t_end, final position.
void run_random_walk(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace);

}  // namespace chaosweep
