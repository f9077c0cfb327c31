#pragma once
// One run of the seed-000 planner family (Algorithm 1): Arnold segments
// (Algorithm 3, SystemScaler) with optional index switching, MapZoning
// transits (Algorithms 2 and 4) and scaling, or Logistic-map segments only.
// Scalar reference; the SIMD kernels reproduce its Arnold steps bit for bit.
#include "arnold_flow.hpp"
#include "coverage_grid.hpp"
#include "environment.hpp"
#include "logistic_map.hpp"
#include "robot_motion.hpp"
#include "run_params.hpp"
#include "trace.hpp"
#include "transit.hpp"
#include "zones.hpp"

namespace chaosweep {

class PlannerRun {
 public:
  // Expects validated parameters and r.t_opt, r.free_cells set.
  PlannerRun(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r,
             TraceSink* trace);
  void run();

  // Single mechanisms, public so tests can drive them on hand-made cases.
  // Algorithm 2: try zones in order until one is reached.
  void map_zoning();
  // Algorithm 4 around Eq. 6: walk a transit to `goal`, rebuilding it from the
  // pushed-out point when it enters an obstacle; false after th attempts (or
  // when the run ended on the way).
  bool transit_to(Point goal);
  Point position() const { return {robot_.x(), robot_.y()}; }
  int th() const { return th_; }
  double time() const { return t_; }

 private:
  // Algorithm 1's loop body for each planner.
  void arnold_loop();
  void logistic_loop();
  // Up to niter Arnold steps; returns the number of new cells.
  long arnold_segment();
  long logistic_segment();
  void arnold_step();

  // Moves the robot (already displaced by the caller), advances the clock by
  // dt and checks every way the run can end. Returns true when it ended.
  bool after_move(double dt, SegmentKind kind);
  void end(Status s, const char* why = nullptr);

  const RunParams& p_;
  const Environment& env_;
  CoverageGrid& grid_;
  RunResult& r_;
  TraceSink* trace_;

  long needed_;
  double budget_;
  ArnoldCoeffs<double> k_;
  Vec3<double> u_;
  int ds_;
  double h_;
  double t_ = 0.0, t_last_new_ = 0.0;
  long last_visited_;
  int th_;
  RobotMotion robot_;
  LogisticMap logistic_;
  Zones zones_;
  bool ended_ = false;
};

// The perturbed Arnold initial state of a run (SPEC 1, "Chaotic spread").
Vec3<double> initial_state(const RunParams& p);

}  // namespace chaosweep
