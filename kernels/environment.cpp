#include "environment.hpp"

#include <algorithm>

namespace chaosweep {

double Environment::obstacle_area() const {
  // Exact union area by coordinate compression: obstacle counts are small.
  std::vector<double> xs, ys;
  for (const Rect& r : obstacles) {
    xs.insert(xs.end(), {std::clamp(r.x0, 0.0, lx), std::clamp(r.x1, 0.0, lx)});
    ys.insert(ys.end(), {std::clamp(r.y0, 0.0, ly), std::clamp(r.y1, 0.0, ly)});
  }
  std::sort(xs.begin(), xs.end());
  std::sort(ys.begin(), ys.end());
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i)
    for (std::size_t j = 0; j + 1 < ys.size(); ++j) {
      const double cx = 0.5 * (xs[i] + xs[i + 1]), cy = 0.5 * (ys[j] + ys[j + 1]);
      if (obstacle_at(cx, cy) >= 0) area += (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]);
    }
  return area;
}

bool push_out_of_obstacles(const Environment& env, double fo, double& x, double& y) {
  return keep_out_of_obstacles(env, fo, false, x, y).moved;
}

ObstacleHit keep_out_of_obstacles(const Environment& env, double fo, bool mirror, double& x, double& y) {
  ObstacleHit hit;
  // A move can land in a neighbour's margin; a few rounds settle any layout
  // whose obstacles are not packed tighter than 2*fo.
  for (int round = 0; round < 8; ++round) {
    bool again = false;
    for (const Rect& r : env.obstacles) {
      const Rect grown{r.x0 - fo, r.y0 - fo, r.x1 + fo, r.y1 + fo};
      if (!grown.contains(x, y)) continue;
      const double to_left = x - grown.x0, to_right = grown.x1 - x;
      const double to_bottom = y - grown.y0, to_top = grown.y1 - y;
      const double m = std::min({to_left, to_right, to_bottom, to_top});
      auto place = [mirror](double& u, double face) { u = mirror ? (face + face) - u : face; };
      if (m == to_left) place(x, grown.x0), ++hit.x_faces;
      else if (m == to_right) place(x, grown.x1), ++hit.x_faces;
      else if (m == to_bottom) place(y, grown.y0), ++hit.y_faces;
      else place(y, grown.y1), ++hit.y_faces;
      hit.moved = again = true;
    }
    if (!again) break;
  }
  return hit;
}

std::vector<unsigned char> cells_clear_of_obstacles(const Environment& env, double fo, int nx, int ny, double cell) {
  std::vector<unsigned char> clear(std::size_t(nx) * std::size_t(ny), 1);
  const double margin = 1e-6 * cell + 1e-9 * std::max(env.lx, env.ly);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x0 = i * cell - margin, y0 = j * cell - margin;
      const double x1 = (i + 1 == nx ? std::max((i + 1) * cell, env.lx) : (i + 1) * cell) + margin;
      const double y1 = (j + 1 == ny ? std::max((j + 1) * cell, env.ly) : (j + 1) * cell) + margin;
      for (const Rect& r : env.obstacles)
        if (x1 > r.x0 - fo && x0 < r.x1 + fo && y1 > r.y0 - fo && y0 < r.y1 + fo) {
          clear[std::size_t(j) * nx + i] = 0;
          break;
        }
    }
  return clear;
}

}  // namespace chaosweep
