// MapZoning (seed 000, Algorithm 2) and LogisticObstacleAvoid (Algorithm 4):
// PlannerRun members (they drive its robot, clock and zones), declared in
// planner_run.hpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

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
  // Point k of the path as the robot would reach it: Eq. 6, then Eq. 7 near
  // the walls, as on Arnold segments.
  const auto mapped = [&](std::size_t k) {
    const Point q = eq6.at(P, k);
    return Point{mirror_eq7(q.x, 0.0, env_.lx, p_.fo), mirror_eq7(q.y, 0.0, env_.ly, p_.fo)};
  };
  const bool open = env_.obstacles.empty();
  int ri = grid_.cell_x(robot_.x()), rj = grid_.cell_y(robot_.y());  // the robot's cell
  // A transit's points fall ten (SR 1) to forty (SR 4) to a cell. While they
  // stay in the robot's cell and that cell marks nothing and meets no
  // obstacle, a point only moves the robot and the clock: after_move could
  // end the run only by the budget or the stuck time then, and such a point
  // takes the full path below. Not with a trace (it records every point) or
  // distance-timed points.
  const bool quiet_ok = trace_ == nullptr && p_.transit_time == TransitTime::points;
  const double stuck = p_.stuck_time > 0 ? p_.stuck_time : std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < P.size(); ++i) {
    // Point i, when the quiet walk below mapped it before handing it on (a
    // walk meanders across cell edges: it stops every few points).
    Point walked{};
    bool have_walked = false;
    if (quiet_ok && grid_.visited_cells() == last_visited_ && grid_.marks_nothing(ri, rj) &&
        (open || cell_clear(ri, rj))) {
      // Clock and count in locals, stored once after the loop (stores at
      // every point made the loop load its members again after each one;
      // measured within noise, BENCHMARKS.md).
      const std::size_t first = i;
      double t = t_, x = 0, y = 0;
      for (; i < P.size(); ++i) {
        walked = mapped(i);
        const double tn = t + p_.dt_c;
        if (!(std::isfinite(walked.x) && std::isfinite(walked.y) && grid_.cell_x(walked.x) == ri &&
              grid_.cell_y(walked.y) == rj && tn < budget_ && tn - t_last_new_ < stuck))
          break;
        t = tn;
        x = walked.x, y = walked.y;
      }
      if (i > first) {
        t_ = t;
        r_.transit_points += std::int64_t(i - first);
        robot_.set_position(x, y, x, y);  // as jump_within
      }
      if (i == P.size()) break;
      have_walked = true;
    }
    auto [x, y] = have_walked ? walked : mapped(i);
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

bool PlannerRun::cell_clear(int i, int j) {
  // Found once per cell and run (0: not yet, 1: clear, 2: not): a transit
  // enters a cell every ten to forty points.
  if (clear_cells_.empty()) clear_cells_.assign(std::size_t(grid_.nx()) * std::size_t(grid_.ny()), 0);
  std::uint8_t& known = clear_cells_[std::size_t(j) * std::size_t(grid_.nx()) + std::size_t(i)];
  if (known == 0) known = meets_no_obstacle(i, j) ? 1 : 2;
  return known == 1;
}

bool PlannerRun::meets_no_obstacle(int i, int j) const {
  // The closed cell, a hair wider (a point's cell comes from x / SR
  // rounded), the last row and column to the map's edge: obstacle_box cuts
  // nothing off it when no obstacle meets it.
  const double cell = grid_.cell_size(), e = 1e-9 * cell;
  const double x1 = i + 1 == grid_.nx() ? std::max((i + 1) * cell, env_.lx) : (i + 1) * cell;
  const double y1 = j + 1 == grid_.ny() ? std::max((j + 1) * cell, env_.ly) : (j + 1) * cell;
  const Rect c{i * cell - e, j * cell - e, x1 + e, y1 + e};
  const Rect b = obstacle_box(env_, 0.0, 0.5 * (c.x0 + c.x1), 0.5 * (c.y0 + c.y1), c, 2 * cell, false).box;
  return b.x0 == c.x0 && b.y0 == c.y0 && b.x1 == c.x1 && b.y1 == c.y1;
}

}  // namespace chaosweep
