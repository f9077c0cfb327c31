#pragma once
// The Chen system (Chen & Ueta 1999), Lorenz's dual:
//   x' = a (y - x),  y' = (c - a) x - x z + c y,  z' = x y - b z.
#include "kernels/systems/flow.hpp"

namespace chaosweep {

struct Chen {
  static constexpr const char* name = "chen";
  static constexpr SystemDefaults defaults{35.0, 3.0, 28.0, 0.0, 3, {"a", "b", "c", ""}, {0.0, 1.0, 0.0}};
  template <class T>
  static Vec3<T> rhs(const Vec3<T>& u, const SystemCoeffs<T>& k) {
    using lane::fma;
    return {k.a * (u.y - u.x), fma(k.c - k.a, u.x, fma(k.c, u.y, -(u.x * u.z))), fma(u.x, u.y, -(k.b * u.z))};
  }
};

}  // namespace chaosweep
