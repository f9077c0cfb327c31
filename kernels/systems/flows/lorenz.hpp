#pragma once
// The Lorenz system (Lorenz 1963), the flow of the Lorenz coverage planners:
//   x' = sigma (y - x),  y' = x (rho - z) - y,  z' = x y - beta z.
#include "kernels/systems/flow.hpp"

namespace chaosweep {

struct Lorenz {
  static constexpr const char* name = "lorenz";
  static constexpr SystemDefaults defaults{10.0,           28.0, 8.0 / 3.0, 0.0, 3, {"sigma", "rho", "beta", ""},
                                           {0.0, 1.0, 0.0}};
  template <class T>
  static Vec3<T> rhs(const Vec3<T>& u, const SystemCoeffs<T>& k) {
    using lane::fma;
    return {k.a * (u.y - u.x), fma(u.x, k.b - u.z, -u.y), fma(u.x, u.y, -(k.c * u.z))};
  }
};

}  // namespace chaosweep
