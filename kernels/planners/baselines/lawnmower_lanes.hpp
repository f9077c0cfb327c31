#pragma once
// The lawnmower's lanes: straight runs through the centres of the coverage
// grid's cells, one per row (or column) of cells, so lanes lie SR apart and
// each sweeps the cells of its row (docs/spec.md §7).
#include <vector>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/geometry.hpp"

namespace chaosweep {

// The centres of the grid's (possibly clipped) cells along x and along y:
// the points CoverageGrid tests to call a cell free.
struct CellCentres {
  std::vector<double> x, y;
  CellCentres(const Environment& env, const CoverageGrid& grid);
};

struct Lane {
  Point lo, hi;  // its ends, lo the one of smaller x (along x) or y
};

// The lanes over the unvisited free cells whose centres lie in `box`
// (closed), one per row of them (along_x) or column, from the first such
// centre to the last, in increasing row (column) order. A free rectangle
// is convex, so its lanes and any straight line between them stay free.
std::vector<Lane> box_lanes(const CoverageGrid& grid, const CellCentres& c, const Rect& box, bool along_x);

// The four ways to drive a rectangle's lanes back and forth: the lanes in
// increasing (corner 0, 1) or decreasing order, the first from lo to hi
// (corner 0, 2) or back, each next one the other way.
inline constexpr int corners = 4;
// The points the robot drives through, in order (two per lane).
std::vector<Point> boustrophedon(const std::vector<Lane>& lanes, int corner);

}  // namespace chaosweep
