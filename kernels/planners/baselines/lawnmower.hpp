#pragma once
// The lawnmower (planner = lawnmower, docs/spec.md §7): the back-and-forth
// path T_opt stands for, made real. The free space is split into rectangles
// (core/rect_decomposition, the Chebyshev planner's, with no radius: the
// robot is a point, as in the coverage model); the robot drives each
// rectangle's lanes through the centres of its unvisited cells back and
// forth, and crosses to the next rectangle by the shortest chain of
// rectangles. Deterministic: no draw, no seed.
#include <string>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

// Why env cannot be decomposed for the lawnmower (too many obstacle edges)
// or p's start lies in no free rectangle, or empty.
std::string validate_lawnmower(const RunParams& p, const Environment& env);

// Fills r: status (ok, timeout, or stuck when every lane it can reach is
// driven short of dc), coverage_time, steps (moves of at most `step`),
// segments (rectangles driven), t_end, final position.
void run_lawnmower(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace);

}  // namespace chaosweep
