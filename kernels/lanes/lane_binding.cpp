#include "kernels/lanes/lane_binding.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

#include "kernels/core/metrics.hpp"
#include "kernels/systems/logistic_map.hpp"

namespace chaosweep {

Vec3<double> LaneBinding::lane_state(const LaneArrays& a, int l) const {
  Vec3<double> u{a.x[l], a.y[l], a.z[l]};
  with_system(run_.sys_, [&](auto tag) {
    using F = typename decltype(tag)::type;
    if constexpr (CarriedSystem<F>) u = F::from_lane(u, run_.ds_);
  });
  return u;
}

Trig3<double> LaneBinding::lane_trig(const LaneArrays& a, int l) const {
  Trig3<double> t = run_.trig_;  // a system that carries nothing
  with_system(run_.sys_, [&](auto tag) {
    using F = typename decltype(tag)::type;
    if constexpr (CarriedSystem<F>)
      t = F::from_lane(Trig3<double>{a.sx[l], a.cx[l], a.sy[l], a.cy[l], a.sz[l], a.cz[l]}, run_.ds_);
  });
  return t;
}

// A system's step inputs (LaneArrays::system): its state as labelled, no carry.
void LaneBinding::write_system_step(LaneArrays& a, int l) const {
  a.x[l] = run_.u_.x;
  a.y[l] = run_.u_.y;
  a.z[l] = run_.u_.z;
  a.sx[l] = a.sy[l] = a.sz[l] = 0.0;
  a.cx[l] = a.cy[l] = a.cz[l] = 1.0;
  a.kA[l] = run_.fk_.a;
  a.kB[l] = run_.fk_.b;
  a.kC[l] = run_.fk_.c;
  a.kD[l] = run_.fk_.d;
  a.ds[l] = run_.ds_;
  a.h[l] = run_.h_;
  a.h_pos[l] = run_.p_.f * run_.p_.v * run_.h_;
  a.pos6[l] = 0.0;
  a.small[l] = 0.0;
}

// A carried system's (CarriedSystem): in its lane labels, its state, carry,
// step constants and mode.
template <class F>
void LaneBinding::write_carried_step(LaneArrays& a, int l) const {
  const Vec3<double> u = F::to_lane(run_.u_, run_.ds_);
  const Trig3<double> t = F::to_lane(run_.trig_, run_.ds_);
  const StepScale<double> sc = F::scale(F::to_lane(run_.fk_, run_.ds_), run_.h_, run_.p_.f * run_.p_.v * run_.h_);
  a.x[l] = u.x;
  a.y[l] = u.y;
  a.z[l] = u.z;
  a.sx[l] = t.sx;
  a.cx[l] = t.cx;
  a.sy[l] = t.sy;
  a.cy[l] = t.cy;
  a.sz[l] = t.sz;
  a.cz[l] = t.cz;
  a.kA[l] = sc.kh.A;
  a.kB[l] = sc.kh.B;
  a.kC[l] = sc.kh.C;
  a.pos6[l] = sc.pos6;
  a.small[l] = F::small(run_.fk_, run_.h_) ? 1.0 : 0.0;
}

// The Logistic planner's (LogisticMap::lane_step): its iterate, r, the
// segment's branch, the fixed point and the robot's distance per point.
void LaneBinding::write_logistic_step(LaneArrays& a, int l) const {
  a.x[l] = run_.planner_x_;
  a.y[l] = a.z[l] = 0.0;
  a.sx[l] = a.sy[l] = a.sz[l] = 0.0;
  a.cx[l] = a.cy[l] = a.cz[l] = 1.0;
  a.kA[l] = run_.p_.logistic_r;
  a.kB[l] = LogisticMap::branch(run_.rightwards_);
  a.kC[l] = LogisticMap::fixed_point(run_.p_.logistic_r);
  a.kD[l] = 0.0;
  a.ds[l] = 1.0;
  a.h[l] = run_.p_.dt_c;
  a.h_pos[l] = run_.p_.dt_c * run_.p_.v;  // logistic_loop's factor of the heading
  a.pos6[l] = 0.0;
  a.small[l] = 0.0;
}

void LaneBinding::write_lane(LaneArrays& a, int l) {
  if (logistic()) {
    write_logistic_step(a, l);
  } else {
    with_system(run_.sys_, [&](auto tag) {
      using F = typename decltype(tag)::type;
      if constexpr (CarriedSystem<F>) write_carried_step<F>(a, l);
      else write_system_step(a, l);
    });
  }
  write_robot(a, l);
}

void LaneBinding::write_robot(LaneArrays& a, int l) {
  a.X[l] = run_.robot_.x();
  a.Y[l] = run_.robot_.y();
  a.t[l] = run_.t_;
  a.fh[l] = logistic() ? run_.p_.dt_c : run_.p_.f * run_.h_;  // the clock step after_move adds
  a.budget[l] = run_.budget_;
  a.stuck_time[l] = run_.p_.stuck_time > 0 ? run_.p_.stuck_time : std::numeric_limits<double>::infinity();
  a.t_last_new[l] = run_.t_last_new_;
  a.steps[l] = double(run_.r_.steps);
  a.seg_step[l] = run_.seg_step_;
  a.niter[l] = run_.p_.niter;
  // A bouncing robot's displacement takes signs the vector code does not
  // apply: its steps all go to the scalar path (correct first; fast later).
  const bool bounces = run_.p_.obstacle_response == ObstacleResponse::reflect && !run_.env_.obstacles.empty();
  // The lanes mark cells as a segment does: an entry stamps Eq. 5's window
  // on the cell left and the one entered, a step within a cell stamps
  // nothing. A point (sampling = points) stamps the cell each step ends in,
  // so a windowed run's counts differ (both with entries made here and with
  // entries left to the scalar path): those runs take the scalar path.
  const bool point_windows = run_.p_.sampling == Sampling::points && run_.p_.map_zoning;
  a.fast[l] = run_.trace_ != nullptr || bounces || point_windows ? 0.0 : 2.0;
  // Steps into a diagonal neighbour too (fast = 3, segments sampling: a
  // point marks only its end cell) when the robot's step is a sizeable part
  // of a cell: there they were most of the steps left to the sink (the
  // map-zoning runs of Table 1, f 1.5-6 on 1 m cells). With short steps they
  // are rare, and the kernel form that takes them measured up to 1.06x the
  // CPU time on five-squares maps (BENCHMARKS.md "Diagonal steps in the lanes").
  const double step_cells =
      (logistic() ? run_.p_.dt_c * run_.p_.v : run_.p_.f * run_.p_.v * run_.h_) * run_.grid_.inv_cell_size();
  if (a.fast[l] == 2.0 && run_.p_.sampling == Sampling::segments && step_cells >= diagonal_step_cells) a.fast[l] = 3.0;
  // The band RobotMotion::move folds into: mirror_eq7's triangle_fold(u,
  // 0 + fo, lx - fo), or the fold boundary's triangle_fold(ux, 0, lx).
  const bool fold = run_.p_.boundary == Boundary::fold;
  a.fold[l] = fold ? 1.0 : 0.0;
  a.UX[l] = run_.robot_.unfolded_x();
  a.UY[l] = run_.robot_.unfolded_y();
  a.lo_x[l] = fold ? 0.0 : 0.0 + run_.p_.fo;
  a.hi_x[l] = fold ? run_.env_.lx : run_.env_.lx - run_.p_.fo;
  a.lo_y[l] = fold ? 0.0 : 0.0 + run_.p_.fo;
  a.hi_y[l] = fold ? run_.env_.ly : run_.env_.ly - run_.p_.fo;
  a.inv_cell[l] = run_.grid_.inv_cell_size();
  a.max_i[l] = run_.grid_.nx() - 1;
  a.max_j[l] = run_.grid_.ny() - 1;
  a.cells[l] = run_.grid_.cell_bytes();
  a.visited[l] = run_.grid_.visited_cells();
  a.cover_sum[l] = run_.grid_.cover_time_sum();
  a.stamp[l] = run_.grid_.window_stamps();
  a.window[l] = run_.grid_.window();
  a.region[l] = run_.grid_.region_of_cell();
  a.region_visited[l] = run_.grid_.region_visited_counts();
  a.visits[l] = run_.grid_.visit_counts();
  a.turns[l] = run_.grid_.turn_counts();
  lane_cell(a, l);
  a.needed[l] = double(run_.needed_);
  a.obstacles[l] = !run_.env_.obstacles.empty();
  lane_box(a, l);
}

void LaneBinding::lane_box(LaneArrays& a, int l) const {
  const Rect band{a.lo_x[l], a.lo_y[l], a.hi_x[l], a.hi_y[l]};
  ObstacleBox b{band, no_rect};
  if (a.obstacles[l]) {
    // Made anew after every step the sink takes, the robot inside the old
    // box or not: a robot pushed onto the face of an obstacle cut off the
    // box stays on the box's edge, and its steps into that obstacle would
    // all be the sink's (two thirds of the sink's steps on Table 1's five
    // squares). The fast path moves a position onto or about the face only
    // on the mirror boundary (the fold also moves the unfolded position) and
    // as the push and mirror responses do (a bounce also reverses the
    // motion): else no obstacle is near.
    // The box reaches as far as the band: the obstacles cut it anyway (a
    // map with an index caps the query itself), and boxes of 16 cells' reach
    // were most of the lanes' stops on Table 1's 200 m five squares.
    const bool pushes = run_.p_.boundary == Boundary::mirror && run_.p_.obstacle_response != ObstacleResponse::reflect;
    const double reach = std::max(band.x1 - band.x0, band.y1 - band.y0);
    b = obstacle_box(run_.env_, run_.p_.fo, run_.robot_.x(), run_.robot_.y(), band, reach, pushes);
  }
  a.box_x0[l] = b.box.x0;
  a.box_x1[l] = b.box.x1;
  a.box_y0[l] = b.box.y0;
  a.box_y1[l] = b.box.y1;
  a.near_x0[l] = b.near.x0;
  a.near_x1[l] = b.near.x1;
  a.near_y0[l] = b.near.y0;
  a.near_y1[l] = b.near.y1;
  a.near_mirror[l] = run_.p_.obstacle_response == ObstacleResponse::mirror ? 1.0 : 0.0;
}

void LaneBinding::lane_cell(LaneArrays& a, int l) const {
  a.cell_i[l] = run_.grid_.cell_x(run_.robot_.x());
  a.cell_j[l] = run_.grid_.cell_y(run_.robot_.y());
  a.cell_k[l] = long(a.cell_j[l]) * run_.grid_.nx() + long(a.cell_i[l]);
  a.window_distinct[l] = run_.grid_.window_distinct();
  a.last_dir[l] = run_.grid_.last_direction();
}

void LaneBinding::take_lane_progress(const LaneArrays& a, int l) {
  run_.robot_.set_position(a.X[l], a.Y[l], a.UX[l], a.UY[l]);
  run_.t_ = a.t[l];
  run_.r_.steps = std::int64_t(a.steps[l]);
  run_.seg_step_ = int(a.seg_step[l]);
  run_.grid_.set_visited_cells(int(a.visited[l]));
  run_.grid_.set_cover_time_sum(a.cover_sum[l]);
  run_.grid_.set_window_distinct(a.window_distinct[l]);
  run_.grid_.set_entry_state(a.cell_k[l], a.last_dir[l]);
  run_.last_visited_ = run_.grid_.visited_cells();
  run_.t_last_new_ = a.t_last_new[l];
}

bool LaneBinding::lane_step(LaneArrays& a, int l) {
  take_lane_progress(a, l);
  bool segment_or_end;
  if (logistic()) {
    run_.planner_x_ = a.x[l];
    segment_or_end = run_.logistic_step_done(a.y[l] == 0.0, a.dX[l], a.dY[l]);  // y: NaN when unusable
  } else {
    segment_or_end = run_.arnold_step_done(lane_state(a, l), lane_trig(a, l), a.dX[l], a.dY[l]);
  }
  if (run_.ended_) return true;
  if (segment_or_end) {  // DSindex, the branch or the robot may have changed: all of it
    write_lane(a, l);
    return false;
  }
  a.X[l] = run_.robot_.x();
  a.Y[l] = run_.robot_.y();
  a.UX[l] = run_.robot_.unfolded_x();
  a.UY[l] = run_.robot_.unfolded_y();
  a.t[l] = run_.t_;
  a.steps[l] = double(run_.r_.steps);
  a.seg_step[l] = run_.seg_step_;
  a.t_last_new[l] = run_.t_last_new_;
  a.visited[l] = run_.grid_.visited_cells();
  a.cover_sum[l] = run_.grid_.cover_time_sum();
  lane_cell(a, l);
  lane_box(a, l);
  return false;
}

bool LaneBinding::lane_covered(LaneArrays& a, int l) {
  take_lane_progress(a, l);
  if (!logistic()) run_.u_ = lane_state(a, l);
  run_.end(Status::ok);  // after_move's first check that holds (the integrator checked the position)
  return true;
}

}  // namespace chaosweep
