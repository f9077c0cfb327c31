#pragma once
// A MapZoning transit path (seed 000, Eq. 6): m Logistic-map positions P_i from
// the start, plus a correction Q_i linearly spaced from start - P_1 to
// goal - P_m, so the mapped path P'_i = P_i + Q_i starts at the robot and ends
// at the goal while keeping the Logistic map's chaotic wiggle.
#include <vector>

#include "logistic_map.hpp"

namespace chaosweep {

struct Point {
  double x, y;
};

// m = floor(d / (v dt_c)) + 1 points (at least 2), the first the start, the
// last the goal. Advances `map` once per generated step; returns an empty
// path when the Logistic orbit degenerates. The heading branch is chosen once
// for the path: rightwards when the goal lies to the right.
std::vector<Point> transit_path(Point start, Point goal, double v, double dt_c, LogisticMap& map);

}  // namespace chaosweep
