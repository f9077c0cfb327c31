#pragma once
// Seeded random clutter (seed 000, Fig. 7: about 8% occupancy).
#include <cstdint>
#include <vector>

#include "environment.hpp"

namespace chaosweep {

struct ClutterSpec {
  std::uint64_t seed = 1;
  double occupancy = 0.08;  // target fraction of the map covered
  double min_side = 1.5, max_side = 4.0;  // square sides, m
  double gap = 1.0;         // clearance between squares, the walls and the start, m
};

// Squares placed at random until their area reaches occupancy * lx * ly (or
// no more fit after many tries). Deterministic in spec.seed.
std::vector<Rect> generate_clutter(double lx, double ly, const ClutterSpec& spec, double start_x,
                                   double start_y);

}  // namespace chaosweep
