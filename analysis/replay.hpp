#pragma once
// Re-runs a stored run from its row: a run is a pure function of its
// parameters, so its trajectory need not be stored. Used by the trajectory
// and coverage figures; the replay is checked against the stored outputs.
#include <string>
#include <vector>

#include "analysis/result_set.hpp"
#include "engine/spec/run_tuple.hpp"
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

struct Replay {
  RunTuple tuple;
  RunResult result;
  std::vector<TracePoint> points;
  std::vector<int> visited;  // visited free cells after each point
  CoverageGrid grid;         // cells covered at the end
  // Empty when the replay reproduces every stored column bit for bit (but
  // wall_time); else the columns that differ (another engine version wrote
  // the file, or an environment file changed).
  std::string mismatch;
};

// The row holding run_id `id` (AnalysisError naming the id when absent or
// when several files hold it).
std::size_t row_of_run(const ResultSet& rs, std::int64_t id);

// Rebuilds row r's run (parameters from the parameter-table columns, the
// environment by name) and runs it with a trace. Throws AnalysisError.
Replay replay_row(const ResultSet& rs, std::size_t r);

}  // namespace chaosweep
