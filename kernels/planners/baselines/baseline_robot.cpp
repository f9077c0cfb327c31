#include "kernels/planners/baselines/baseline_robot.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/core/metrics.hpp"
#include "kernels/core/run_end.hpp"
#include "kernels/math/inline_hypot.hpp"

namespace chaosweep {

BaselineRobot::BaselineRobot(const RunParams& p, CoverageGrid& grid, RunResult& r, TraceSink* trace)
    : grid_(grid),
      r_(r),
      trace_(trace),
      needed_(cells_needed(p, grid)),
      budget_(run_budget(p, r.t_opt)),
      step_(p.step),
      v_(p.v),
      points_(p.sampling == Sampling::points),
      x_(p.start_x),
      y_(p.start_y),
      cell_(grid, p.start_x, p.start_y) {
  grid_.mark_point(x_, y_);
  grid_.note_time(0.0);
  if (trace_) trace_->point({0.0, x_, y_, SegmentKind::start, 0});
  if (grid_.visited_cells() >= needed_) end(Status::ok);
}

void BaselineRobot::move(double nx, double ny, double dt, SegmentKind kind) {
  t_ += dt;  // the move's end time
  ++moves_;
  const bool entered = cell_.mark_move(grid_, points_, x_, y_, nx, ny);
  if (entered) grid_.note_time(t_);
  x_ = nx, y_ = ny;
  if (trace_) trace_->point({t_, x_, y_, kind, 0});
  if (entered && grid_.visited_cells() >= needed_) end(Status::ok);
  else if (t_ >= budget_) end(Status::timeout, "budget reached before dc");
}

void BaselineRobot::walk_to(double gx, double gy, SegmentKind kind) {
  const double dist = inline_hypot(gx - x_, gy - y_);
  if (ended_ || dist == 0) return;
  // Equal moves (dist / moves up to rounding), each charged that length:
  // one hypot per walk. Positions are interpolated from the walk's start,
  // m * d / moves rounded once, so that no rounding accumulates along a
  // lane and a position the grid has exactly (a cell's edge) is hit
  // exactly: coverage times are exact on a grid of binary fractions.
  const long moves = std::max<long>(1, long(std::ceil(dist / step_)));
  const double dt = dist / double(moves) / v_;
  const double sx = x_, sy = y_, dx = gx - sx, dy = gy - sy;
  for (long m = 1; m <= moves && !ended_; ++m) {
    if (m == moves) move(gx, gy, dt, kind);
    else move(sx + double(m) * dx / double(moves), sy + double(m) * dy / double(moves), dt, kind);
  }
}

void BaselineRobot::end(Status s, const char* why) {
  if (ended_) return;
  ended_ = true;
  record_end(r_, s, why, t_, x_, y_);
  r_.steps = moves_;
}

}  // namespace chaosweep
