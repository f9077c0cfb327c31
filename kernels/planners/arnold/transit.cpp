#include "kernels/planners/arnold/transit.hpp"

#include <cmath>

#include "kernels/math/inline_hypot.hpp"

namespace chaosweep {

std::vector<Point> logistic_positions(Point start, Point goal, double v, double dt_c, LogisticOrbit& map) {
  const double d = inline_hypot(goal.x - start.x, goal.y - start.y);
  const std::size_t m = std::max<std::size_t>(2, std::size_t(std::floor(d / (v * dt_c))) + 1);
  const bool rightwards = goal.x >= start.x;
  std::vector<Point> p(m);
  p[0] = start;
  for (std::size_t i = 1; i < m; ++i) {
    const LogisticOrbit::Heading h = map.next(rightwards);
    if (!h.ok) return {};
    p[i] = {p[i - 1].x + dt_c * v * h.cos, p[i - 1].y + dt_c * v * h.sin};
  }
  return p;
}

void map_positions(const std::vector<Point>& P, std::size_t from, Point first, Point goal, std::vector<Point>& path) {
  const std::size_t m = P.size();
  path.resize(m);
  const Point q0{first.x - P[from].x, first.y - P[from].y};
  const Point q1{goal.x - P[m - 1].x, goal.y - P[m - 1].y};
  const double span = double(m - 1 - from);
  for (std::size_t k = from; k < m; ++k) {
    const double s = double(k - from) / span;
    path[k] = {P[k].x + (1.0 - s) * q0.x + s * q1.x, P[k].y + (1.0 - s) * q0.y + s * q1.y};
  }
  path[from] = first;  // exact, whatever the rounding of the corrections
  path[m - 1] = goal;
}

std::vector<Point> transit_path(Point start, Point goal, double v, double dt_c, LogisticOrbit& map) {
  std::vector<Point> p = logistic_positions(start, goal, v, dt_c, map);
  if (!p.empty()) map_positions(p, 0, start, goal, p);
  return p;
}

}  // namespace chaosweep
