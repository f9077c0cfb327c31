#pragma once
// The Logistic map x' = r x (1 - x) driving a robot heading (seed 000, Eqs. 2
// and 4): theta = pi x - pi/2 moves the robot rightwards, pi x + pi/2 leftwards.
#include <cmath>
#include <numbers>

namespace chaosweep {

struct LogisticMap {
  double x = 0.1;
  double r = 4.0;

  // Advances the map; false when the orbit is degenerate (a fixed point 0 or
  // 1 - 1/r, or outside [0, 1]): the run then ends as diverged.
  bool step() {
    x = r * x * (1.0 - x);
    return x > 0.0 && x <= 1.0 && x != 1.0 - 1.0 / r;
  }

  // Heading for the current state; rightwards = the "-pi/2" branch of Eq. 4.
  double heading(bool rightwards) const { return std::numbers::pi * x + (rightwards ? -0.5 : 0.5) * std::numbers::pi; }
};

}  // namespace chaosweep
