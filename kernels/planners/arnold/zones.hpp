#pragma once
// MapZoning's zones (seed 000, Algorithm 2): the map split into zx x zy
// rectangles, each with its midpoint and coverage density.
#include <memory>
#include <vector>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"

namespace chaosweep {

struct ZoneInfo {
  int index;
  double mid_x, mid_y;    // the zone's midpoint
  double goal_x, goal_y;  // where a transit to this zone goes (see Zones)
  bool has_goal;
  int free_cells, visited_cells;
  double density() const { return free_cells > 0 ? double(visited_cells) / free_cells : 1.0; }
};

// Transit goals. Paper-literal (free_goal = false): the midpoint, even inside
// an obstacle, where every transit fails after th attempts. Default
// (free_goal = true): the midpoint when it is at least fo clear of every
// obstacle, else the centre of the zone's free cell nearest to it that is;
// a zone with no such cell has no goal and is not a candidate.
class Zones {
 public:
  Zones(const Environment& env, const CoverageGrid& grid, int zx, int zy, bool free_goal, double fo);
  int count() const { return zx_ * zy_; }
  int zone_of(double x, double y) const;
  // The zone of each grid cell (row-major), for CoverageGrid::count_regions.
  const std::shared_ptr<const std::vector<int>>& cell_zones() const { return cell_zone_; }
  // Densities now (each free cell belongs to the zone holding its centre):
  // O(zones) from the grid's own counts when it counts by cell_zones(), else
  // a pass over the grid.
  std::vector<ZoneInfo> snapshot(const CoverageGrid& grid) const;

 private:
  double lx_, ly_;
  int zx_, zy_;
  std::shared_ptr<const std::vector<int>> cell_zone_;  // zone of each grid cell
  std::vector<ZoneInfo> base_;  // midpoints, goals and free cells; visited cells filled by snapshot()
};

// The Zones of (env, grid, zx, zy, free_goal, fo), shared by every run that
// asks for the same: built once per distinct map, grid and parameters
// (kernels/core/setup_cache.hpp), equal to Zones(env, grid, ...).
std::shared_ptr<const Zones> shared_zones(const Environment& env, const CoverageGrid& grid, int zx, int zy,
                                          bool free_goal, double fo);

// Candidate zones in the order MapZoning tries them (docs/spec.md §2): zones with a free
// cell and a goal, except the robot's. Lowest density first, ties by distance
// to the goal; or (distance_first) nearest goal first, ties by lowest density.
// Remaining ties by zone index.
std::vector<ZoneInfo> zone_order(std::vector<ZoneInfo> zones, int robot_zone, double x, double y, bool distance_first);

// Whether a run ranks zones distance first: zone_order = auto does on maps
// with obstacles only (Section 3.2), density and distance always the one way.
bool zones_distance_first(ZoneOrder order, bool obstacles);

}  // namespace chaosweep
