#pragma once
// Seeded random clutter (seed 000, Fig. 7: about 8% occupancy).
#include <cstdint>
#include <vector>

#include "kernels/core/environment.hpp"

namespace chaosweep {

struct ClutterSpec {
  std::uint64_t seed = 1;
  double occupancy = 0.08;                // target fraction of the map covered
  double min_side = 1.5, max_side = 4.0;  // square sides, m
  double gap = 1.0;                       // clearance between squares, the walls and the start, m
};

// Attempts at placing a square: the generator stops after this many even
// when the occupancy is not reached (no more fit).
inline constexpr int max_clutter_attempts = 100000;

// Squares placed at random until their area reaches occupancy * lx * ly (or
// no more fit after max_clutter_attempts tries). Deterministic in spec.seed.
std::vector<Rect> generate_clutter(double lx, double ly, const ClutterSpec& spec, double start_x, double start_y);

}  // namespace chaosweep
