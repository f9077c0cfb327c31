#pragma once
// The Chirikov standard map (Chirikov 1979), the kicked rotor, a
// two-dimensional area-preserving chaotic map whose coordinates are angles:
//   y' = y + K sin x,  x' = x + y'   (both mod 2 pi, here wrapped to [-pi, pi]).
// Beyond K ~ 1 its chaotic sea spans the torus, so the heading x (or y)
// takes every direction with no drift: unlike a map of a line segment
// (Henon's x in [-1.3, 1.3]), no scale is needed to turn it into an angle.
#include "kernels/systems/chaotic_map.hpp"

namespace chaosweep {

struct Chirikov {
  static constexpr const char* name = "chirikov";
  static constexpr SystemDefaults defaults{6.0, 0.0, 0.0, 0.0, 1, {"K", "", "", ""}, {0.5, 0.25, 0.0}};
  static constexpr int dimension = 2;
  static constexpr double heading_scale[3] = {1.0, 1.0, 0.0};
  template <class T>
  static Vec3<T> iterate(const Vec3<T>& u, const SystemCoeffs<T>& k) {
    T s, c;
    sincos(u.x, s, c);
    const T y = wrap_pi(lane::fma(k.a, s, u.y));
    return {wrap_pi(u.x + y), y, u.z};
  }
};

}  // namespace chaosweep
