#pragma once
// The cell of a robot that moves in short straight moves, and the marking of
// each move on the coverage grid. A move that ends in the robot's cell marks
// nothing new: that cell was marked when the robot entered it, and a cell is
// convex (most moves are shorter than a cell, so most are such); coverage,
// checked after every mark, cannot have grown without one.
#include "kernels/core/coverage_grid.hpp"

namespace chaosweep {

class CellTracker {
 public:
  // At (x, y), whose cell is marked already.
  CellTracker(const CoverageGrid& g, double x, double y) : ci_(g.cell_x(x)), cj_(g.cell_y(y)) {}

  // Marks the move (x, y) -> (nx, ny) unless it ends in the robot's cell:
  // the cells of its segment, or with `points` the cell of its end only.
  // Whether it left the cell (only then can coverage have grown).
  bool mark_move(CoverageGrid& g, bool points, double x, double y, double nx, double ny) {
    const int ni = g.cell_x(nx), nj = g.cell_y(ny);
    if (ni == ci_ && nj == cj_) return false;
    if (points) g.mark_cell(ni, nj);
    else g.mark_step(ci_, cj_, ni, nj, x, y, nx, ny);
    ci_ = ni, cj_ = nj;
    return true;
  }

 private:
  int ci_, cj_;
};

}  // namespace chaosweep
