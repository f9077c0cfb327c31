#pragma once
// Seed 001, Section 5.1: the free space of a rectangular workplace with
// rectangular obstacles, split into small rectangles along the obstacles'
// edges (Sz), merged into feasible coverage rectangles (SI_x) and linked by
// transition rectangles (ST_y). Everything is computed on the geometry after
// edge expansion: the workplace shrunk and the obstacles grown by the robot
// radius, so a robot centre inside any of these rectangles keeps its body
// clear of walls and obstacles. In core/ because the lawnmower baseline
// (planners/baselines/) covers the same rectangles with radius 0.
#include <string>
#include <vector>

#include "kernels/core/environment.hpp"

namespace chaosweep {

struct RectDecomposition {
  struct Small {
    Rect box;
    int i, j;    // column and row in the grid of cut lines
    int region;  // the SI_x it was merged into
  };
  struct Region {  // SI_x: a rectangle made of small rectangles
    Rect box;
    std::vector<int> small;
    double area() const { return (box.x1 - box.x0) * (box.y1 - box.y0); }
  };
  struct Transition {  // ST_y: small rectangles on both sides of a shared edge
    Rect box;
    int a, b;  // the regions it links
    std::vector<int> small;
  };
  std::vector<double> xs, ys;  // cut lines
  std::vector<Small> small;
  std::vector<Region> regions;
  std::vector<Transition> transitions;

  // The region whose rectangle holds (x, y) (closed), or -1.
  int region_at(double x, double y) const;
  // Transitions linking regions a and b, or -1.
  int transition_between(int a, int b) const;
  // Regions adjacent to r through a transition.
  std::vector<int> neighbours(int r) const;
};

// The most cells of cut lines a decomposition takes: its merging step grows
// faster than quadratically in them (measured: 50 scattered obstacles give
// about 1e4 cells and a run took 1.8 s; 100 give 4e4 and took 69 s; 200 did
// not end in 300 s), so more is refused.
inline constexpr double max_decomposition_cells = 16384;

// Throws std::invalid_argument when the radius leaves no free space, or when
// the obstacles cut more than max_decomposition_cells cells.
RectDecomposition decompose_free_space(const Environment& env, double radius);

// "Sz" names for messages and figures: the paper's letters in its order are
// figure-specific, so rectangles are named by their cut-grid cell, "c<i>r<j>".
std::string small_name(const RectDecomposition& d, int s);

}  // namespace chaosweep
