#pragma once
// Reference times and coverage thresholds of docs/spec.md §1.
#include <cmath>

namespace chaosweep {

// Back-and-forth lawnmower time to cover dc of the free area: dc*A_free/(SR*v).
// Reproduces the PR column of Table 1 (seed 000).
inline double t_opt(double dc, double free_area, double sr, double v) {
  return dc * free_area / (sr * v);
}

// Smallest number of visited free cells k with k / free >= dc, computed
// without trusting dc * free to round the right way.
inline long cells_needed(double dc, long free_cells) {
  long k = static_cast<long>(std::ceil(dc * double(free_cells)));
  while (k > 0 && double(k - 1) / double(free_cells) >= dc) --k;
  while (double(k) / double(free_cells) < dc) ++k;
  return k;
}

}  // namespace chaosweep
