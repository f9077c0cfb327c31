#include "kernels/planners/baselines/random_walk.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernels/core/param_table.hpp"
#include "kernels/math/splitmix.hpp"
#include "kernels/planners/baselines/baseline_robot.hpp"
#include "kernels/planners/baselines/free_space.hpp"

namespace chaosweep {

std::string validate_random_walk(const RunParams& p, const Environment& env) {
  if (!(p.step < std::min(env.lx, env.ly)))
    return "step = " + format_number(p.step) + " must be shorter than the map's shorter side (" +
           format_number(std::min(env.lx, env.ly)) + " m) for planner = random_walk";
  return {};
}

void run_random_walk(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace) {
  BaselineRobot robot(p, grid, r, trace);
  std::uint64_t rng = std::uint64_t(p.seed);
  const double dt = p.step / p.v;
  while (!robot.ended()) {
    // Drawing again until the move is free makes the heading uniform over
    // the free headings (rejection sampling).
    double nx = 0, ny = 0;
    for (int draws = 0;; ++draws) {
      if (draws == max_redraws) return robot.end(Status::stuck, "every heading drawn leaves the free space");
      const double heading = 2.0 * std::numbers::pi * uniform01(rng);
      nx = robot.x() + p.step * std::cos(heading), ny = robot.y() + p.step * std::sin(heading);
      if (move_stays_free(env, robot.x(), robot.y(), nx, ny)) break;
      ++r.reflections;
    }
    robot.move(nx, ny, dt, SegmentKind::move);
  }
}

}  // namespace chaosweep
