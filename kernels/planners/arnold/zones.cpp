#include "kernels/planners/arnold/zones.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace chaosweep {

Zones::Zones(const Environment& env, const CoverageGrid& grid, int zx, int zy, bool free_goal, double fo)
    : lx_(env.lx), ly_(env.ly), zx_(zx), zy_(zy) {
  auto clear = [&](double x, double y) { return !env.near_obstacle(x, y, fo); };
  base_.resize(static_cast<std::size_t>(count()));
  std::vector<double> best(base_.size(), std::numeric_limits<double>::infinity());
  for (int k = 0; k < count(); ++k) {
    const double mx = (k % zx_ + 0.5) * lx_ / zx_, my = (k / zx_ + 0.5) * ly_ / zy_;
    const bool ok = !free_goal || clear(mx, my);
    base_[std::size_t(k)] = {k, mx, my, mx, my, ok, 0, 0};
    if (ok) best[std::size_t(k)] = -1.0;  // the midpoint itself wins
  }
  cell_zone_.resize(std::size_t(grid.nx()) * grid.ny());
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const double cx = 0.5 * (i * grid.cell_size() + std::min((i + 1) * grid.cell_size(), lx_));
      const double cy = 0.5 * (j * grid.cell_size() + std::min((j + 1) * grid.cell_size(), ly_));
      const int k = zone_of(cx, cy);
      cell_zone_[std::size_t(j) * grid.nx() + i] = k;
      ZoneInfo& z = base_[std::size_t(k)];
      if (!free_goal || grid.at(i, j) == CoverageGrid::blocked || !clear(cx, cy)) continue;
      const double d = std::hypot(cx - z.mid_x, cy - z.mid_y);
      if (d < best[std::size_t(k)]) {
        best[std::size_t(k)] = d;
        z.goal_x = cx;
        z.goal_y = cy;
        z.has_goal = true;
      }
    }
}

int Zones::zone_of(double x, double y) const {
  const int a = std::clamp(int(std::floor(x / lx_ * zx_)), 0, zx_ - 1);
  const int b = std::clamp(int(std::floor(y / ly_ * zy_)), 0, zy_ - 1);
  return b * zx_ + a;
}

std::vector<ZoneInfo> Zones::snapshot(const CoverageGrid& grid) const {
  std::vector<ZoneInfo> z = base_;
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const auto cell = grid.at(i, j);
      if (cell == CoverageGrid::blocked) continue;
      ZoneInfo& zi = z[std::size_t(cell_zone_[std::size_t(j) * grid.nx() + i])];
      ++zi.free_cells;
      zi.visited_cells += cell == CoverageGrid::visited;
    }
  return z;
}

std::vector<ZoneInfo> zone_order(std::vector<ZoneInfo> zones, int robot_zone, double x, double y, bool distance_first) {
  std::erase_if(zones, [&](const ZoneInfo& z) { return z.free_cells == 0 || !z.has_goal || z.index == robot_zone; });
  auto key = [&](const ZoneInfo& z) {
    const double d = std::hypot(z.goal_x - x, z.goal_y - y);
    return distance_first ? std::tuple{d, z.density(), z.index} : std::tuple{z.density(), d, z.index};
  };
  std::sort(zones.begin(), zones.end(), [&](const ZoneInfo& a, const ZoneInfo& b) { return key(a) < key(b); });
  return zones;
}

bool zones_distance_first(ZoneOrder order, bool obstacles) {
  return order == ZoneOrder::distance || (order == ZoneOrder::automatic && obstacles);
}

}  // namespace chaosweep
