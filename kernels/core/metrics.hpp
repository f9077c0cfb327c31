#pragma once
// Reference times and coverage thresholds of docs/spec.md §1.
#include <algorithm>
#include <cmath>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/run_params.hpp"

namespace chaosweep {

// Back-and-forth lawnmower time to cover dc of the free area: dc*A_free/(SR*v).
// Reproduces the PR column of Table 1 (seed 000).
inline double t_opt(double dc, double free_area, double sr, double v) { return dc * free_area / (sr * v); }

// A run's robot-time budget: max_time, or max_pr T_opt when it is 0 (auto).
inline double run_budget(const RunParams& p, double t_opt) { return p.max_time > 0 ? p.max_time : p.max_pr * t_opt; }

// Smallest number of visited free cells k with k / free >= dc, computed
// without trusting dc * free to round the right way.
inline long cells_needed(double dc, long free_cells) {
  long k = static_cast<long>(std::ceil(dc * double(free_cells)));
  while (k > 0 && double(k - 1) / double(free_cells) >= dc) --k;
  while (double(k) / double(free_cells) < dc) ++k;
  return k;
}

// The cells tc counts beyond the visited free ones, and its denominator
// (Eq. 5's c_T): none and the free cells (docs/spec.md §1), or, with coverage_cells =
// all, the obstacle cells (known to the robot, so covered) and every cell.
inline long cells_counted_covered(const RunParams& p, const CoverageGrid& g) {
  return p.coverage_cells == CoverageCells::all_cells ? g.blocked_cells() : 0;
}
inline long cells_total(const RunParams& p, const CoverageGrid& g) {
  return g.free_cells() + cells_counted_covered(p, g);
}

// Visited free cells a run needs for tc >= dc.
inline long cells_needed(const RunParams& p, const CoverageGrid& g) {
  return std::max(0L, cells_needed(p.dc, cells_total(p, g)) - cells_counted_covered(p, g));
}

// tc with `visited` free cells visited.
inline double coverage_rate(const RunParams& p, const CoverageGrid& g, long visited) {
  return double(visited + cells_counted_covered(p, g)) / double(cells_total(p, g));
}

}  // namespace chaosweep
