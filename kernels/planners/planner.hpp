#pragma once
// The entry point every caller uses: run one planner simulation.
#include <optional>
#include <string>

#include "kernels/core/coverage_grid.hpp"

#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

// Why (p, env) cannot run, or empty. Checks ranges, the map, the start point.
std::string validate_run(const RunParams& p, const Environment& env);

// A pure function of its arguments: never throws for bad input (the result
// says `invalid`), never depends on anything but p and env. The map's size is
// env.lx x env.ly; p.size_x/size_y are carried for the record only.
RunResult run_planner(const RunParams& p, const Environment& env);
// The same, reporting every trajectory point to `trace` (may be null).
RunResult run_planner(const RunParams& p, const Environment& env, TraceSink* trace);

// The two ends of a run, shared by run_planner and the lane driver: validate
// and set up the grid and reference values (false: r says why it is invalid),
// and fill the coverage outputs once the run has ended.
bool prepare_run(const RunParams& p, const Environment& env, std::optional<CoverageGrid>& grid, RunResult& r);
void conclude_run(const RunParams& p, const CoverageGrid& grid, RunResult& r);

}  // namespace chaosweep
