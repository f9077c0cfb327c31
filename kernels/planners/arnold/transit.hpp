#pragma once
// A MapZoning transit path (seed 000, Eq. 6): m Logistic-map positions P_i from
// the start, plus a correction Q_i linearly spaced from start - P_1 to
// goal - P_m, so the mapped path P'_i = P_i + Q_i starts at the robot and ends
// at the goal while keeping the Logistic map's chaotic wiggle.
#include <cstddef>
#include <vector>

#include "kernels/core/geometry.hpp"
#include "kernels/planners/arnold/logistic_orbit.hpp"

namespace chaosweep {

// m = floor(d / (v dt_c)) + 1 Logistic positions P (at least 2), the first
// the start. Draws from `map` once per generated step; returns an empty path
// when the Logistic orbit degenerates. The heading branch is chosen once for
// the path: rightwards when the goal lies to the right.
std::vector<Point> logistic_positions(Point start, Point goal, double v, double dt_c, LogisticOrbit& map);
// The same into `p` (its storage reused): false, p empty, when the orbit degenerates.
bool logistic_positions(Point start, Point goal, double v, double dt_c, LogisticOrbit& map, std::vector<Point>& p);

// Eq. 6 from index `from` on, one point at a time: at(P, k) = P[k] + Q[k] for
// k >= from, with Q linear from first - P[from] to goal - P[m-1], so that
// at(P, from) = first and at(P, m-1) = goal exactly. Needs from < m - 1. A
// walk that may stop early (a transit that meets an obstacle) maps only the
// points it reaches.
class Eq6Map {
 public:
  Eq6Map() = default;
  Eq6Map(const std::vector<Point>& P, std::size_t from, Point first, Point goal)
      : from_(from),
        last_(P.size() - 1),
        span_(double(P.size() - 1 - from)),
        first_(first),
        goal_(goal),
        q0_{first.x - P[from].x, first.y - P[from].y},
        q1_{goal.x - P[P.size() - 1].x, goal.y - P[P.size() - 1].y} {}
  Point at(const std::vector<Point>& P, std::size_t k) const {
    if (k == from_) return first_;  // exact, whatever the rounding of the corrections
    if (k == last_) return goal_;
    const double s = double(k - from_) / span_;
    return {P[k].x + (1.0 - s) * q0_.x + s * q1_.x, P[k].y + (1.0 - s) * q0_.y + s * q1_.y};
  }

 private:
  std::size_t from_ = 0, last_ = 0;
  double span_ = 1.0;
  Point first_{}, goal_{}, q0_{}, q1_{};
};

// Eq. 6 from index `from` on into path (path[k] = Eq6Map(P, from, first,
// goal).at(P, k) for k >= from; path resized to P's size).
void map_positions(const std::vector<Point>& P, std::size_t from, Point first, Point goal, std::vector<Point>& path);

// The mapped path from start to goal (logistic_positions, then Eq. 6 from 0).
std::vector<Point> transit_path(Point start, Point goal, double v, double dt_c, LogisticOrbit& map);

}  // namespace chaosweep
