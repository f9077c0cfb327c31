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

// Eq. 6 from index `from` on: path[k] = P[k] + Q[k] for k >= from, with Q
// linear from first - P[from] to goal - P[m-1], so that path[from] = first and
// path[m-1] = goal exactly. Needs from < m - 1.
void map_positions(const std::vector<Point>& P, std::size_t from, Point first, Point goal, std::vector<Point>& path);

// The mapped path from start to goal (logistic_positions, then Eq. 6 from 0).
std::vector<Point> transit_path(Point start, Point goal, double v, double dt_c, LogisticOrbit& map);

}  // namespace chaosweep
