#pragma once
// The Chebyshev-map planner of seed 001 in the common coverage model: two
// Chebyshev maps give sub-goals, mapped affinely (Eqs. 10-11) into the
// rectangle the robot is working in; the robot walks straight to each
// sub-goal in steps of p.step. With obstacles, the free space is decomposed
// (core/rect_decomposition.hpp) and covered in large loops (Section 5.2): each
// coverage rectangle gets its share of p.loop_subgoals by area, then the
// robot leaves through a transition rectangle to the next one.
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/rect_decomposition.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

// Why (p, env) cannot run as a Chebyshev run (the start outside the free
// space shrunk by the radius, no free space), or empty.
std::string validate_chebyshev(const RunParams& p, const Environment& env);

// Runs until coverage reaches p.dc, the budget or p.max_subgoals; fills r
// (status, coverage_time, steps = robot moves, subgoals, segments = large
// loops, t_end, final position). The grid must be fresh.
void run_chebyshev(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace);

// The order in which one large loop visits the coverage rectangles from
// `from`: depth-first over the transition graph, with the rectangles passed
// through on the way back listed again (each pair of consecutive entries is
// linked by a transition). Every rectangle reachable from `from` appears.
std::vector<int> loop_route(const RectDecomposition& d, int from);

}  // namespace chaosweep
