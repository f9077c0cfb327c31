#pragma once
// The robot the baselines share: a point at speed v that moves in straight
// lines, marks the cells of each move on the coverage grid, and ends the run
// at dc (ok) or at the budget (timeout, max_time or max_pr * T_opt), like the
// other planners of the common model (docs/spec.md §1).
#include <cstdint>

#include "kernels/core/cell_tracker.hpp"
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

class BaselineRobot {
 public:
  // At p.start, its cell marked (a run that needs no more ends ok at once).
  BaselineRobot(const RunParams& p, CoverageGrid& grid, RunResult& r, TraceSink* trace);

  double x() const { return x_; }
  double y() const { return y_; }
  bool ended() const { return ended_; }

  // One straight move to (nx, ny) taking robot time dt; then the end checks.
  void move(double nx, double ny, double dt, SegmentKind kind);
  // Straight to (gx, gy) in equal moves no longer than p.step, the last
  // landing on it exactly; stops early if the run ends.
  void walk_to(double gx, double gy, SegmentKind kind);
  // Ends the run (the first call wins) and records status, times, moves
  // (r.steps) and the final position.
  void end(Status s, const char* why = nullptr);

 private:
  CoverageGrid& grid_;
  RunResult& r_;
  TraceSink* trace_;
  const long needed_;
  const double budget_, step_, v_;
  const bool points_;  // sampling = points: a move marks only its end's cell
  double x_, y_, t_ = 0;
  CellTracker cell_;
  std::int64_t moves_ = 0;
  bool ended_ = false;
};

}  // namespace chaosweep
