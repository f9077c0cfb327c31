#pragma once
// One run of the seed-000 planner family (Algorithm 1): Arnold segments
// (Algorithm 3, SystemScaler) with optional index switching, MapZoning
// transits (Algorithms 2 and 4) and scaling, or Logistic-map segments only.
// Scalar reference; the SIMD kernels reproduce its Arnold steps bit for bit.
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/robot_motion.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/core/trace.hpp"
#include "kernels/planners/arnold/logistic_orbit.hpp"
#include "kernels/planners/arnold/transit.hpp"
#include "kernels/planners/arnold/zones.hpp"
#include "kernels/systems/arnold_flow.hpp"
#include "kernels/systems/system_list.hpp"

namespace chaosweep {

class PlannerRun {
 public:
  // Expects validated parameters and r.t_opt, r.free_cells set.
  PlannerRun(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace);
  void run();

  // Step-driven use, for steps computed elsewhere (the lane integrators;
  // kernels/lanes/lane_binding.hpp marshals the run into a lane and back):
  // start(), arnold_step_done() per step until ended(), then finish().
  void start();
  bool ended() const { return ended_; }
  void finish();

  // The scalar reference path's step, exposed for the lane driver's tests.
  bool arnold_step_done(const Vec3<double>& u, const Trig3<double>& t, double dX, double dY);
  // The Logistic planner's step: its iterate usable (else the run ends
  // diverged), the robot's displacement. True when the run ended or a new
  // segment began (its branch chosen).
  bool logistic_step_done(bool ok, double dX, double dY);

  // Single mechanisms, public so tests can drive them on hand-made cases;
  // defined in map_zoning.cpp (Algorithms 2 and 4).
  // Algorithm 2: try zones in order until one is reached.
  void map_zoning();
  // Algorithm 4 around Eq. 6: walk a transit to `goal`, rebuilding it from the
  // pushed-out point when it enters an obstacle; false after th attempts (or
  // when the run ended on the way).
  bool transit_to(Point goal);
  Point position() const { return {robot_.x(), robot_.y()}; }
  int th() const { return th_; }
  double logistic_state() const { return logistic_.x(); }  // the transits' orbit's
  double time() const { return t_; }

 private:
  void logistic_loop();
  void begin_logistic_segment();
  // One step of the run's chaotic system on the scalar path (fixed step or
  // step doubling; the Arnold flow or a flow of system_list.hpp).
  void arnold_step();
  template <class Step>
  void take_point(const Step& step);
  // After an Arnold point: clock, end checks, segment bookkeeping.
  bool point_done(double dt);
  void begin_segment();
  void end_segment();

  // Moves the robot (already displaced by the caller), advances the clock by
  // dt and checks every way the run can end. Returns true when it ended.
  [[gnu::always_inline]] inline bool after_move(double dt, SegmentKind kind);
  void end(Status s, const char* why = nullptr);
  // The run's zones, made at the first need (map zoning on: at the start),
  // the grid counting visited cells by zone from then on.
  const Zones& zones();
  // Whether no point of cell (i, j) lies in an obstacle: meets_no_obstacle,
  // kept per cell in clear_cells_ (transit_to).
  bool cell_clear(int i, int j);
  bool meets_no_obstacle(int i, int j) const;
  // The lane marshalling copies the whole state into a lane and back: a
  // friend rather than accessors for every member.
  friend class LaneBinding;

  const RunParams& p_;
  const Environment& env_;
  CoverageGrid& grid_;
  RunResult& r_;
  TraceSink* trace_;

  long needed_;
  double budget_;
  int sys_;                  // RunParams::system
  SystemCoeffs<double> fk_;  // the system's coefficients (system_coeffs: Arnold's A, B, C)
  Vec3<double> u_;
  // A carried system's carry of u_ (the Arnold flow: its trig, carried by
  // rk4_step). u_ changes by its steps alone (not by switching, zoning or
  // transits); taken afresh at the start and at every segment's start (a
  // pure function of the run, like its segments).
  Trig3<double> trig_;
  int ds_;
  double h_;
  double t_ = 0.0, t_last_new_ = 0.0;
  long last_visited_;
  int th_;
  RobotMotion robot_;
  LogisticOrbit logistic_;                 // the transits' (MapZoning)
  double planner_x_;                       // the Logistic planner's iterate, from the same x0
  std::shared_ptr<const Zones> zones_;     // null until zones()
  std::vector<Point> transit_positions_;   // transit_to's, kept for their storage
  std::vector<std::uint8_t> clear_cells_;  // see cell_clear (empty until its first use)
  bool ended_ = false;
  bool rightwards_ = true;  // the Logistic planner's branch in this segment
  int seg_step_ = 0;
  long seg_before_ = 0, seg_c_u_ = 0;
};

inline bool PlannerRun::after_move(double dt, SegmentKind kind) {
  t_ += dt;
  if (trace_) trace_->point({t_, robot_.x(), robot_.y(), kind, ds_});
  if (grid_.visited_cells() != last_visited_) {
    last_visited_ = grid_.visited_cells();
    t_last_new_ = t_;
    grid_.note_time(t_);
  }
  if (!std::isfinite(robot_.x()) || !std::isfinite(robot_.y())) end(Status::diverged, "non-finite position");
  else if (grid_.visited_cells() >= needed_) end(Status::ok);
  else if (t_ >= budget_) end(Status::timeout);
  else if (p_.stuck_time > 0 && t_ - t_last_new_ >= p_.stuck_time) end(Status::stuck);
  return ended_;
}

// The run's jittered ic (jittered_ic, kernels/core/chaotic_spread.hpp),
// for the Arnold flow wrapped into [-pi, pi] (its state is angles).
Vec3<double> initial_state(const RunParams& p);
// The Logistic map a run starts from (and, with logistic_reset = drop,
// restarts from when a zone is dropped).
LogisticOrbit initial_logistic(const RunParams& p);

}  // namespace chaosweep
