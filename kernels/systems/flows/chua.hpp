#pragma once
// Chua's circuit (dimensionless, piecewise-linear diode), the double scroll:
//   x' = alpha (y - x - g(x)),  y' = x - y + z,  z' = -beta y,
//   g(x) = m1 x + (m0 - m1) (|x + 1| - |x - 1|) / 2.
#include "kernels/systems/flow.hpp"

namespace chaosweep {

struct Chua {
  static constexpr const char* name = "chua";
  // The initial state lies in the double scroll's basin: the piecewise-linear
  // circuit's orbits from (0, 1, 0) grow without bound.
  static constexpr SystemDefaults defaults{
      15.6, 28.0, -8.0 / 7.0, -5.0 / 7.0, 4, {"alpha", "beta", "m0", "m1"}, {0.7, 0.0, 0.0}};
  template <class T>
  static Vec3<T> rhs(const Vec3<T>& u, const SystemCoeffs<T>& k) {
    using lane::fma;
    const T one = lane::splat<T>(1.0);
    const T kink = flow_abs(u.x + one) - flow_abs(u.x - one);
    const T g = fma(k.c - k.d, kink * lane::splat<T>(0.5), k.d * u.x);
    return {k.a * (u.y - u.x - g), (u.x - u.y) + u.z, -(k.b * u.y)};
  }
};

}  // namespace chaosweep
