#include "kernels/planners/baselines/lawnmower_lanes.hpp"

#include <algorithm>

namespace chaosweep {

namespace {

std::vector<double> centres(int n, double cell, double side) {
  std::vector<double> c(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) c[std::size_t(i)] = 0.5 * (i * cell + std::min((i + 1) * cell, side));
  return c;
}

// The indices of the centres in [lo, hi].
std::pair<int, int> centres_in(const std::vector<double>& c, double lo, double hi) {
  return {int(std::lower_bound(c.begin(), c.end(), lo) - c.begin()),
          int(std::upper_bound(c.begin(), c.end(), hi) - c.begin())};
}

}  // namespace

CellCentres::CellCentres(const Environment& env, const CoverageGrid& grid)
    : x(centres(grid.nx(), grid.cell_size(), env.lx)), y(centres(grid.ny(), grid.cell_size(), env.ly)) {}

std::vector<Lane> box_lanes(const CoverageGrid& grid, const CellCentres& c, const Rect& box, bool along_x) {
  const auto [i0, i1] = centres_in(c.x, box.x0, box.x1);
  const auto [j0, j1] = centres_in(c.y, box.y0, box.y1);
  const auto open = [&](int i, int j) { return grid.at(i, j) == CoverageGrid::unvisited; };
  std::vector<Lane> lanes;
  // Along x: row j from its first open column to its last; along y, the same with rows and columns swapped.
  const int rows0 = along_x ? j0 : i0, rows1 = along_x ? j1 : i1;
  const int cols0 = along_x ? i0 : j0, cols1 = along_x ? i1 : j1;
  for (int row = rows0; row < rows1; ++row) {
    int first = -1, last = -1;
    for (int col = cols0; col < cols1; ++col)
      if (along_x ? open(col, row) : open(row, col)) {
        if (first < 0) first = col;
        last = col;
      }
    if (first < 0) continue;
    if (along_x) {
      const double y = c.y[std::size_t(row)];
      lanes.push_back({{c.x[std::size_t(first)], y}, {c.x[std::size_t(last)], y}});
    } else {
      const double x = c.x[std::size_t(row)];
      lanes.push_back({{x, c.y[std::size_t(first)]}, {x, c.y[std::size_t(last)]}});
    }
  }
  return lanes;
}

std::vector<Point> boustrophedon(const std::vector<Lane>& lanes, int corner) {
  std::vector<Point> path;
  const std::size_t n = lanes.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Lane& lane = lanes[corner < 2 ? k : n - 1 - k];
    const bool forward = (corner % 2 == 0) == (k % 2 == 0);
    path.push_back(forward ? lane.lo : lane.hi);
    path.push_back(forward ? lane.hi : lane.lo);
  }
  return path;
}

}  // namespace chaosweep
