#pragma once
// How a planner's run ended, recorded in its result the same way by the
// planners that move a robot in straight moves.
#include "kernels/core/run_params.hpp"

namespace chaosweep {

// The status (and why, if given), the robot time and position at the end,
// and the coverage time when the run reached dc (ok).
inline void record_end(RunResult& r, Status s, const char* why, double t, double x, double y) {
  r.status = s;
  if (why) r.message = why;
  if (s == Status::ok) r.coverage_time = t;
  r.t_end = t;
  r.final_x = x, r.final_y = y;
}

}  // namespace chaosweep
