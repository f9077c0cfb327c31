#pragma once
// One run of the seed-000 planner family (Algorithm 1): Arnold segments
// (Algorithm 3, SystemScaler) with optional index switching, MapZoning
// transits (Algorithms 2 and 4) and scaling, or Logistic-map segments only.
// Scalar reference; the SIMD kernels reproduce its Arnold steps bit for bit.
#include <cmath>

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

  // Step-driven use by the lane integrators, which compute fixed-step RK4
  // steps of many runs at once: start(), then per step read arnold_lane(),
  // hand back the step with arnold_step_done() until ended(), then finish().
  struct ArnoldLane {
    Vec3<double> u;
    double A, B, C, h, h_pos;
    int ds;
  };
  void start();
  ArnoldLane arnold_lane() const;
  // Applies one accepted Arnold step and, at the end of a segment, the
  // decisions of Algorithm 1 (Eq. 5, index switching, MapZoning transits run
  // here, scalar). True when the lane must reload arnold_lane(): a segment
  // ended (DSindex may have changed) or the run ended.
  bool arnold_step_done(const Vec3<double>& u, double dX, double dY);
  bool ended() const { return ended_; }
  void finish();

  // What the lane fast path needs (see LaneArrays), and the progress it made
  // handed back before the next full step.
  struct LaneProgress {
    double x, y, t, fh, budget, stuck_time, t_last_new;
    std::int64_t steps;
    int seg_step, niter;
    bool fast;  // mirror boundary, no obstacles, no trace
    double lo_x, hi_x, lo_y, hi_y, inv_cell;
    int max_i, max_j, cell_i, cell_j;
  };
  LaneProgress lane_progress() const;
  void set_lane_progress(double x, double y, double t, std::int64_t steps, int seg_step);

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
  void logistic_loop();
  long logistic_segment();
  // One Arnold step of the scalar path (fixed step or step doubling).
  void arnold_step();
  // After an Arnold point: clock, end checks, segment bookkeeping.
  bool point_done(double dt);
  void begin_segment();
  void end_segment();

  // Moves the robot (already displaced by the caller), advances the clock by
  // dt and checks every way the run can end. Returns true when it ended.
  [[gnu::always_inline]] inline bool after_move(double dt, SegmentKind kind);
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
  int seg_step_ = 0;
  long seg_before_ = 0, seg_c_u_ = 0;
};

inline bool PlannerRun::after_move(double dt, SegmentKind kind) {
  t_ += dt;
  if (trace_) trace_->point({t_, robot_.x(), robot_.y(), kind, ds_});
  if (grid_.visited_cells() != last_visited_) {
    last_visited_ = grid_.visited_cells();
    t_last_new_ = t_;
  }
  if (!std::isfinite(robot_.x()) || !std::isfinite(robot_.y())) end(Status::diverged, "non-finite position");
  else if (grid_.visited_cells() >= needed_) end(Status::ok);
  else if (t_ >= budget_) end(Status::timeout);
  else if (p_.stuck_time > 0 && t_ - t_last_new_ >= p_.stuck_time) end(Status::stuck);
  return ended_;
}

// The perturbed Arnold initial state of a run (SPEC 1, "Chaotic spread").
Vec3<double> initial_state(const RunParams& p);

}  // namespace chaosweep
