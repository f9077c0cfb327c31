#include "transit.hpp"

#include <cmath>

namespace chaosweep {

std::vector<Point> transit_path(Point start, Point goal, double v, double dt_c, LogisticMap& map) {
  const double d = std::hypot(goal.x - start.x, goal.y - start.y);
  const std::size_t m = std::max<std::size_t>(2, std::size_t(std::floor(d / (v * dt_c))) + 1);
  const bool rightwards = goal.x >= start.x;
  std::vector<Point> p(m);
  p[0] = start;
  for (std::size_t i = 1; i < m; ++i) {
    if (!map.step()) return {};
    const double th = map.heading(rightwards);
    p[i] = {p[i - 1].x + dt_c * v * std::cos(th), p[i - 1].y + dt_c * v * std::sin(th)};
  }
  // Q_1 = start - P_1 = 0; Q_m = goal - P_m.
  const Point q_end{goal.x - p[m - 1].x, goal.y - p[m - 1].y};
  for (std::size_t i = 1; i < m; ++i) {
    const double s = double(i) / double(m - 1);
    p[i].x += s * q_end.x;
    p[i].y += s * q_end.y;
  }
  p[m - 1] = goal;  // exact, whatever the rounding of s * q_end
  return p;
}

}  // namespace chaosweep
