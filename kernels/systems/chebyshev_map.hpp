#pragma once
// The Chebyshev map of order k, x' = cos(k arccos x) on [-1, 1] (seed 001,
// Eq. 1), and the transforms that flatten its arcsine-distributed orbit
// (Eqs. 4-5). docs/spec.md §3: the map iterates on x and the planner uses the
// transformed value u; the transform never feeds back into the map.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernels/systems/cheb_transform.hpp"

namespace chaosweep {

// One iteration; the argument is clamped into [-1, 1] so rounding at the
// ends (|x| = 1 + ulp) never produces NaN.
inline double chebyshev_step(double x, int k) { return std::cos(k * std::acos(std::clamp(x, -1.0, 1.0))); }

// arcsine: (2/pi) asin x in [-1, 1]; arccosine: (2/pi) acos x in [0, 2];
// none: x itself.
inline double cheb_transform(double x, ChebTransform t) {
  const double c = std::clamp(x, -1.0, 1.0);
  switch (t) {
    case ChebTransform::arcsine:
      return 2.0 / std::numbers::pi * std::asin(c);
    case ChebTransform::arccosine:
      return 2.0 / std::numbers::pi * std::acos(c);
    case ChebTransform::none:
      break;
  }
  return c;
}

// The transformed value's range, for mapping it affinely onto a rectangle.
inline double cheb_lo(ChebTransform t) { return t == ChebTransform::arccosine ? 0.0 : -1.0; }
inline double cheb_hi(ChebTransform t) { return t == ChebTransform::arccosine ? 2.0 : 1.0; }

}  // namespace chaosweep
