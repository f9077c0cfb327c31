#include "kernels/planners/arnold/planner_run.hpp"

#include <cmath>
#include <cstdint>

#include "kernels/core/chaotic_spread.hpp"
#include "kernels/core/metrics.hpp"
#include "kernels/math/splitmix.hpp"
#include "kernels/planners/arnold/control.hpp"
#include "kernels/systems/logistic_map.hpp"

namespace chaosweep {

namespace {

bool finite(const Vec3<double>& u) { return std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z); }

int auto_th(const RunParams& p, const Environment& env) {
  if (p.th > 0) return p.th;
  // Paper: th = 10 on 50 m maps, higher on larger maps (docs/spec.md §2: 10 * L / 50).
  return std::max(1, int(std::lround(10.0 * std::max(env.lx, env.ly) / 50.0)));
}

}  // namespace

Vec3<double> initial_state(const RunParams& p) { return system_start(p.system, jittered_ic(p)); }

LogisticOrbit initial_logistic(const RunParams& p) {
  double x0 = p.logistic_x0;
  if (p.logistic_jitter > 0) {
    std::uint64_t s = std::uint64_t(p.seed);
    for (int k = 0; k < 3; ++k) (void)uniform_pm1(s);  // the draws of initial_state, whether used or not
    x0 += p.logistic_jitter * uniform_pm1(s);
  }
  return {p.logistic_r, x0};
}

PlannerRun::PlannerRun(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace)
    : p_(p),
      env_(env),
      grid_(grid),
      r_(r),
      trace_(trace),
      needed_(cells_needed(p, grid)),
      budget_(run_budget(p, r.t_opt)),
      sys_(p.system),
      fk_(system_coeffs(p)),
      u_(initial_state(p)),
      trig_(system_carry(p.system, u_, {})),
      ds_(p.ds_index),
      h_(p.dt),
      last_visited_(0),
      th_(auto_th(p, env)),
      robot_(p, env, grid),
      logistic_(initial_logistic(p)),
      planner_x_(logistic_.x()) {
  // Only map zoning uses the zones (their setup was 60% of a 200 m map's).
  if (p.map_zoning) zones();
  last_visited_ = grid_.visited_cells();
  grid_.note_time(0.0);  // the start cell
  if (trace_) trace_->point({0.0, robot_.x(), robot_.y(), SegmentKind::start, ds_});
}

const Zones& PlannerRun::zones() {
  if (!zones_) {
    zones_ = shared_zones(env_, grid_, p_.zones_x, p_.zones_y, p_.zone_goal == ZoneGoal::free_cell, p_.fo);
    grid_.count_regions(zones_->cell_zones(), zones_->count());
  }
  return *zones_;
}

void PlannerRun::end(Status s, const char* why) {
  ended_ = true;
  r_.status = s;
  if (why) r_.message = why;
  if (s == Status::ok) r_.coverage_time = t_;
}

void PlannerRun::start() {
  // The start cell alone may already satisfy a tiny dc.
  if (grid_.visited_cells() >= needed_) end(Status::ok);
  else if (p_.planner == Planner::arnold) begin_segment();
  else begin_logistic_segment();
}

void PlannerRun::finish() {
  r_.t_end = t_;
  r_.final_x = robot_.x();
  r_.final_y = robot_.y();
  r_.final_ds_index = ds_;
}

void PlannerRun::run() {
  start();
  if (p_.planner == Planner::logistic) logistic_loop();
  else
    while (!ended_) arnold_step();
  finish();
}

// ------------------------------------------------------------- Algorithm 1

void PlannerRun::begin_segment() {
  ++r_.segments;
  if (p_.map_zoning) grid_.begin_window();
  seg_c_u_ = grid_.free_cells() - grid_.visited_cells();  // unvisited before the segment
  seg_before_ = grid_.visited_cells();
  seg_step_ = 0;
  // A segment starts from an exact carry: bounds the carried trig's drift
  // (a system that carries none keeps its `trig_` unused).
  trig_ = system_carry(sys_, u_, trig_);
}

void PlannerRun::end_segment() {
  const long c_n = grid_.visited_cells() - seg_before_;
  const bool keep_exploring =
      !p_.map_zoning || eq5_keep_exploring(c_n, grid_.window_distinct(), seg_c_u_, cells_total(p_, grid_), p_.c);
  if (!keep_exploring) {
    map_zoning();
  } else if (p_.index_switching && c_n <= p_.switch_min_new) {
    ds_ = next_ds_index(ds_, system_dimension(sys_));
    ++r_.index_switches;
  }
  if (!ended_) begin_segment();
}

bool PlannerRun::point_done(double dt) {
  if (after_move(dt, SegmentKind::arnold)) return true;
  if (++seg_step_ < p_.niter) return false;
  end_segment();
  return true;
}

bool PlannerRun::arnold_step_done(const Vec3<double>& u, const Trig3<double>& t, double dX, double dY) {
  robot_.move(dX, dY);
  u_ = u;
  trig_ = t;
  r_.steps += 1;
  if (!finite(u_)) {
    end(Status::diverged, "non-finite chaotic state");
    return true;
  }
  return point_done(p_.f * h_);
}

// One point of the scalar path by `step(u, trig, h, h_pos)` (an Rk4Step of
// the run's system): fixed step, or step doubling.
template <class Step>
void PlannerRun::take_point(const Step& step) {
  const double h_pos = p_.f * p_.v * h_;
  const Rk4Step<double> full = step(u_, trig_, h_, h_pos);
  if (p_.integrator == Integrator::rk4_doubling) {
    const double hh = 0.5 * h_, hh_pos = 0.5 * h_pos;
    const Rk4Step<double> a = step(u_, trig_, hh, hh_pos);
    const Rk4Step<double> b = step(a.u, a.t, hh, hh_pos);
    if (std::fabs(full.dX - (a.dX + b.dX)) > p_.ep || std::fabs(full.dY - (a.dY + b.dY)) > p_.ep) {
      // Accept the two half steps (one point) and keep dt/2 for the rest of the run.
      robot_.move(a.dX, a.dY);
      robot_.move(b.dX, b.dY);
      u_ = b.u;
      trig_ = b.t;
      const double dt_used = h_;
      h_ = hh;
      r_.steps += 2;
      ++r_.dt_halvings;
      if (!finite(u_)) return end(Status::diverged, "non-finite chaotic state");
      if (point_done(p_.f * dt_used)) return;
      if (h_ < p_.dt_min) end(Status::diverged, "step doubling shrank dt below dt_min");
      return;
    }
  }
  arnold_step_done(full.u, full.t, full.dX, full.dY);
}

void PlannerRun::arnold_step() {
  const HeadingSelect<double> hs = heading_select(ds_);
  with_system(sys_, [&](auto tag) {
    using F = typename decltype(tag)::type;
    take_point([&](const Vec3<double>& u, const Trig3<double>& t, double h, double h_pos) {
      return step_with_carry<F>(u, t, fk_, hs, h, h_pos);
    });
  });
}

// ----------------------------------------------------- Logistic map only

// The planner's map is its own (planner_x_), not the transits' orbit: its
// point is LogisticMap::step, as in the lanes (LogisticMap::lane_step).
void PlannerRun::logistic_loop() {
  const double r = p_.logistic_r, fixed = LogisticMap::fixed_point(r), dtv = p_.dt_c * p_.v;
  while (!ended_) {
    const LogisticMap::Step<double> q = LogisticMap::step(planner_x_, r, LogisticMap::branch(rightwards_), fixed, dtv);
    planner_x_ = q.x;
    logistic_step_done(q.ok, q.dX, q.dY);
  }
}

void PlannerRun::begin_logistic_segment() {
  ++r_.segments;
  // The heading branch is chosen once per segment: rightwards from the left half.
  rightwards_ = robot_.x() < 0.5 * env_.lx;
  seg_step_ = 0;
}

bool PlannerRun::logistic_step_done(bool ok, double dX, double dY) {
  if (!ok) {
    end(Status::diverged, "Logistic map reached a fixed point");
    return true;
  }
  robot_.move(dX, dY);
  ++r_.steps;
  if (after_move(p_.dt_c, SegmentKind::logistic)) return true;
  if (++seg_step_ < p_.niter) return false;
  begin_logistic_segment();
  return true;
}

}  // namespace chaosweep
