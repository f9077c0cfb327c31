#include "kernels/planners/arnold/transit.hpp"

#include <cmath>

#include "kernels/math/inline_hypot.hpp"

namespace chaosweep {

bool logistic_positions(Point start, Point goal, double v, double dt_c, LogisticOrbit& map, std::vector<Point>& p) {
  const double d = inline_hypot(goal.x - start.x, goal.y - start.y);
  const std::size_t m = std::max<std::size_t>(2, std::size_t(std::floor(d / (v * dt_c))) + 1);
  const bool rightwards = goal.x >= start.x;
  p.resize(m);
  p[0] = start;
  // The running position in registers: read back from p, each point waited
  // on the store of the one before.
  double x = start.x, y = start.y;
  Point* at = p.data() + 1;
  const bool ok = map.headings(long(m - 1), rightwards, [&](double cos, double sin) {
    x = x + dt_c * v * cos;
    y = y + dt_c * v * sin;
    *at++ = {x, y};
  });
  if (!ok) p.clear();
  return ok;
}

std::vector<Point> logistic_positions(Point start, Point goal, double v, double dt_c, LogisticOrbit& map) {
  std::vector<Point> p;
  logistic_positions(start, goal, v, dt_c, map, p);
  return p;
}

void map_positions(const std::vector<Point>& P, std::size_t from, Point first, Point goal, std::vector<Point>& path) {
  const Eq6Map eq6(P, from, first, goal);
  path.resize(P.size());
  for (std::size_t k = from; k < P.size(); ++k) path[k] = eq6.at(P, k);
}

std::vector<Point> transit_path(Point start, Point goal, double v, double dt_c, LogisticOrbit& map) {
  std::vector<Point> p = logistic_positions(start, goal, v, dt_c, map);
  if (!p.empty()) map_positions(p, 0, start, goal, p);
  return p;
}

}  // namespace chaosweep
