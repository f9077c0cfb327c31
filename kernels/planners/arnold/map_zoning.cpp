// MapZoning (seed 000, Algorithm 2) and LogisticObstacleAvoid (Algorithm 4):
// PlannerRun members (they drive its robot, clock and zones), declared in
// planner_run.hpp.
#include <cmath>

#include "kernels/core/boundary.hpp"
#include "kernels/math/inline_hypot.hpp"
#include "kernels/planners/arnold/planner_run.hpp"

namespace chaosweep {

void PlannerRun::map_zoning() {
  ++r_.zonings;
  const Zones& zones = this->zones();
  std::vector<bool> dropped(std::size_t(zones.count()), false);
  for (;;) {
    // Re-ranked from wherever the robot now is: failed transits move it.
    const auto order = zone_order(zones.snapshot(grid_), zones.zone_of(robot_.x(), robot_.y()), robot_.x(), robot_.y(),
                                  zones_distance_first(p_.zone_order, !env_.obstacles.empty()));
    const ZoneInfo* next = nullptr;
    for (const ZoneInfo& z : order)
      if (!dropped[std::size_t(z.index)]) {
        next = &z;
        break;
      }
    if (!next) {
      th_ += p_.dnh;  // every zone failed: be more patient next time
      return;
    }
    if (transit_to({next->goal_x, next->goal_y})) {
      ++r_.transits;
      return;
    }
    if (ended_) return;
    dropped[std::size_t(next->index)] = true;
    ++r_.zones_dropped;
    // Algorithm 2 keeps only the Logistic map's initial conditions (line 36).
    if (p_.logistic_reset == LogisticReset::drop) logistic_ = initial_logistic(p_);
  }
}

bool PlannerRun::transit_to(Point goal) {
  int attempts = 0;
  // P: the Logistic positions (storage kept from transit to transit), mapped
  // by Eq. 6 point by point as the robot reaches them (from the robot, or
  // from the last pushed-out point on).
  std::vector<Point>& P = transit_positions_;
  Eq6Map eq6;
  auto fresh_path = [&](Point from) {
    if (!logistic_positions(from, goal, p_.v, p_.dt_c, logistic_, P))
      return end(Status::diverged, "Logistic map reached a fixed point"), false;
    eq6 = Eq6Map(P, 0, from, goal);
    return true;
  };
  if (!fresh_path(position())) return false;
  const bool open = env_.obstacles.empty();
  int ri = grid_.cell_x(robot_.x()), rj = grid_.cell_y(robot_.y());  // the robot's cell
  for (std::size_t i = 1; i < P.size(); ++i) {
    const Point q = eq6.at(P, i);
    // Eq. 7 near the walls, as on Arnold segments.
    double x = mirror_eq7(q.x, 0.0, env_.lx, p_.fo);
    double y = mirror_eq7(q.y, 0.0, env_.ly, p_.fo);
    const bool blocked = !open && env_.obstacle_at(x, y) >= 0;
    // Eq. 8 as the Arnold steps read it (a transit point has no motion to reverse).
    if (blocked) keep_out_of_obstacles(env_, p_.fo, p_.obstacle_response != ObstacleResponse::push, x, y);
    const Point from = position();
    const int ci = grid_.cell_x(x), cj = grid_.cell_y(y);
    if (!robot_.jump_within(x, y, ci, cj, ri, rj)) robot_.jump_to(x, y);
    ri = ci;
    rj = cj;
    ++r_.transit_points;
    // The mapped points are not v dt_c apart (Eq. 6 adds the correction Q):
    // dt_c each is Algorithm 4's clock, distance / v the robot's speed.
    const double dt = p_.transit_time == TransitTime::points ? p_.dt_c : inline_hypot(x - from.x, y - from.y) / p_.v;
    if (after_move(dt, SegmentKind::transit)) return false;
    if (!blocked) continue;
    ++r_.transit_attempts;
    if (++attempts >= th_) return false;
    // Rebuild the rest of the path from the pushed-out point: Algorithm 4
    // maps the remaining Logistic points P_i..P_m anew (m <- m - i + 1); a
    // fresh path draws new ones. A blocked goal leaves nothing to reuse.
    if (p_.transit_replan == TransitReplan::reuse && i + 1 < P.size()) {
      eq6 = Eq6Map(P, i, {x, y}, goal);
    } else {
      if (!fresh_path({x, y})) return false;
      i = 0;
    }
  }
  return true;
}

}  // namespace chaosweep
