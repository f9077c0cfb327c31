#include "kernels/planners/arnold/zones.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include "kernels/core/setup_cache.hpp"
#include "kernels/math/inline_hypot.hpp"

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
  auto cell_zone = std::make_shared<std::vector<int>>(std::size_t(grid.nx()) * grid.ny());
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const double cx = 0.5 * (i * grid.cell_size() + std::min((i + 1) * grid.cell_size(), lx_));
      const double cy = 0.5 * (j * grid.cell_size() + std::min((j + 1) * grid.cell_size(), ly_));
      const int k = zone_of(cx, cy);
      (*cell_zone)[std::size_t(j) * grid.nx() + i] = k;
      ZoneInfo& z = base_[std::size_t(k)];
      z.free_cells += grid.at(i, j) != CoverageGrid::blocked;
      if (!free_goal || grid.at(i, j) == CoverageGrid::blocked || !clear(cx, cy)) continue;
      const double d = inline_hypot(cx - z.mid_x, cy - z.mid_y);
      if (d < best[std::size_t(k)]) {
        best[std::size_t(k)] = d;
        z.goal_x = cx;
        z.goal_y = cy;
        z.has_goal = true;
      }
    }
  cell_zone_ = std::move(cell_zone);
}

int Zones::zone_of(double x, double y) const {
  const int a = std::clamp(int(std::floor(x / lx_ * zx_)), 0, zx_ - 1);
  const int b = std::clamp(int(std::floor(y / ly_ * zy_)), 0, zy_ - 1);
  return b * zx_ + a;
}

std::vector<ZoneInfo> Zones::snapshot(const CoverageGrid& grid) const {
  std::vector<ZoneInfo> z = base_;
  if (grid.regions() == cell_zone_.get()) {
    for (ZoneInfo& zi : z) zi.visited_cells = grid.region_visited(zi.index);
    return z;
  }
  const std::vector<int>& cell_zone = *cell_zone_;
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i)
      if (grid.at(i, j) == CoverageGrid::visited)
        ++z[std::size_t(cell_zone[std::size_t(j) * grid.nx() + i])].visited_cells;
  return z;
}

std::shared_ptr<const Zones> shared_zones(const Environment& env, const CoverageGrid& grid, int zx, int zy,
                                          bool free_goal, double fo) {
  // Bounded by cells (4 bytes each in cell_zones): at most 2^24 cells, 64 MiB.
  static SetupCache<Zones> cache(std::size_t(1) << 24);
  SetupKey key;
  // The grid's blocked cells follow from the map and the cell size.
  key.add(env).add(grid.cell_size()).add(grid.nx()).add(grid.ny()).add(zx).add(zy).add(int(free_goal)).add(fo);
  const std::size_t cells = std::size_t(grid.nx()) * std::size_t(grid.ny());
  return cache.get(key, cells, [&] { return std::make_shared<const Zones>(env, grid, zx, zy, free_goal, fo); });
}

std::vector<ZoneInfo> zone_order(std::vector<ZoneInfo> zones, int robot_zone, double x, double y, bool distance_first) {
  std::erase_if(zones, [&](const ZoneInfo& z) { return z.free_cells == 0 || !z.has_goal || z.index == robot_zone; });
  // Each key once: the sort compares every zone several times (a hypot each).
  std::vector<std::pair<std::tuple<double, double, int>, std::size_t>> keys;
  keys.reserve(zones.size());
  for (std::size_t k = 0; k < zones.size(); ++k) {
    const ZoneInfo& z = zones[k];
    const double d = inline_hypot(z.goal_x - x, z.goal_y - y);
    keys.push_back({distance_first ? std::tuple{d, z.density(), z.index} : std::tuple{z.density(), d, z.index}, k});
  }
  std::sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<ZoneInfo> order;
  order.reserve(zones.size());
  for (const auto& key : keys) order.push_back(zones[key.second]);
  return order;
}

bool zones_distance_first(ZoneOrder order, bool obstacles) {
  return order == ZoneOrder::distance || (order == ZoneOrder::automatic && obstacles);
}

}  // namespace chaosweep
