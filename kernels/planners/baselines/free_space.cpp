#include "kernels/planners/baselines/free_space.hpp"

#include <algorithm>

#include "kernels/core/obstacle_index.hpp"

namespace chaosweep {

bool crosses_interior(const Rect& o, double x0, double y0, double x1, double y1) {
  // Liang-Barsky: the parameters [t0, t1] of the segment inside the closed
  // rectangle; it meets the interior iff that piece's midpoint is interior
  // (a piece inside a closed rectangle with its midpoint on the boundary
  // lies along one edge).
  const double dx = x1 - x0, dy = y1 - y0;
  double t0 = 0, t1 = 1;
  const auto clip = [&](double p, double q) {  // keep t with p * t <= q
    if (p == 0) return q >= 0;
    const double t = q / p;
    if (p < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    return t0 <= t1;
  };
  if (!(clip(-dx, x0 - o.x0) && clip(dx, o.x1 - x0) && clip(-dy, y0 - o.y0) && clip(dy, o.y1 - y0))) return false;
  const double t = 0.5 * (t0 + t1);
  return o.contains(x0 + t * dx, y0 + t * dy);
}

bool move_stays_free(const Environment& env, double x0, double y0, double x1, double y1) {
  if (!(x1 > 0 && x1 < env.lx && y1 > 0 && y1 < env.ly)) return false;
  const auto hits = [&](std::size_t k) { return crosses_interior(env.obstacles[k], x0, y0, x1, y1); };
  if (const ObstacleIndex* index = env.usable_index())
    return !index->find(std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1), hits);
  for (std::size_t k = 0; k < env.obstacles.size(); ++k)
    if (hits(k)) return false;
  return true;
}

}  // namespace chaosweep
