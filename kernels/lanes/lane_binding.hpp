#pragma once
// A seed-000 PlannerRun bound to one lane of LaneArrays: copies the run's
// state into lane l for the vector integrators and takes back what they
// advanced. The marshalling lives here, above the planners, so that the
// planner knows nothing of lanes.
#include <vector>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/lanes/lane_arrays.hpp"
#include "kernels/planners/arnold/planner_run.hpp"

namespace chaosweep {

// The robot's step, in cells, from which a lane takes its steps into a
// diagonal neighbour itself (LaneArrays::fast = 3): measured on SR 1 maps
// (bench --variants, before the boxes' cut rule and one function per
// kernel form), at 0.2 (f 2) that kernel form ran 0.92-0.99x the CPU time,
// at 0.1 (f 1) 0.96-0.98x on open maps and 0.99-1.05x on five squares.
inline constexpr double diagonal_step_cells = 0.15;

// Step-driven use of a PlannerRun by the lane integrators, which compute
// fixed-step RK4 steps (or Logistic points) of many runs at once:
// run().start(), write_lane(), then for every step the integrator flags (see
// LaneArrays::flagged) lane_step(), until it returns true (the run ended);
// then run().finish().
class LaneBinding {
 public:
  // Expects what PlannerRun expects; a lane run has no trace.
  LaneBinding(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r)
      : run_(p, env, grid, r, nullptr) {}
  PlannerRun& run() { return run_; }

  void write_lane(LaneArrays& a, int l);
  // Applies the flagged step in full: the robot's move, the cells, the end
  // checks and, at the end of a segment, the decisions of Algorithm 1 (Eq. 5,
  // index switching, MapZoning transits, scalar). Takes over the progress the
  // fast path made since the last call and hands its own back.
  bool lane_step(LaneArrays& a, int l);
  // The integrator applied lane l's step and the new cell it marked reached
  // dc (LaneArrays::covered): ends the run.
  bool lane_covered(LaneArrays& a, int l);

 private:
  // The robot, clock, counts, cells and new-cell time the integrator advanced in lane l.
  void take_lane_progress(const LaneArrays& a, int l);
  // Lane l's system state and its carry in the run's own labels.
  Vec3<double> lane_state(const LaneArrays& a, int l) const;
  Trig3<double> lane_trig(const LaneArrays& a, int l) const;
  // write_lane's parts: the system's step inputs (a carried system's in its
  // lane labels, or any other's), then the robot, clock, grid and fast-path inputs.
  template <class F>
  void write_carried_step(LaneArrays& a, int l) const;
  void write_system_step(LaneArrays& a, int l) const;
  void write_logistic_step(LaneArrays& a, int l) const;
  void write_robot(LaneArrays& a, int l);
  // Lane l's cell and the window's distinct count, from the run.
  void lane_cell(LaneArrays& a, int l) const;

  // Lane l's obstacle box (LaneArrays::box_x0): the band on an open map,
  // else obstacle_box around the robot.
  void lane_box(LaneArrays& a, int l) const;

  // The Logistic planner: its map runs in the lanes (LogisticMap::lane_step).
  bool logistic() const { return run_.p_.planner == Planner::logistic; }

  PlannerRun run_;
};

}  // namespace chaosweep
