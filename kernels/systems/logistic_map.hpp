#pragma once
// The Logistic map x' = r x (1 - x) driving a robot heading (seed 000, Eqs. 2
// and 4): theta = pi x - pi/2 moves the robot rightwards, pi x + pi/2
// leftwards. Written once over the lane type T (math/lane_math.hpp). The
// Logistic planner takes the heading's cosine and sine from sincos.hpp
// (`heading`), so its scalar reference and its lanes compute the same
// numbers; MapZoning's transits take the C library's of the same `angle`
// (planners/arnold/logistic_orbit.hpp says why).
#include <limits>
#include <numbers>

#include "kernels/math/lane_math.hpp"
#include "kernels/math/sincos.hpp"
#include "kernels/systems/system.hpp"

namespace chaosweep {

struct LogisticMap {
  // Eq. 4's branches: theta = pi x + branch * pi.
  static constexpr double rightwards = -0.5, leftwards = 0.5;
  static double branch(bool to_the_right) { return to_the_right ? rightwards : leftwards; }

  // x' = r x (1 - x).
  template <class T>
  static T iterate(T x, T r) {
    return r * x * (lane::splat<T>(1.0) - x);
  }
  // The value 1 - 1/r of `usable`.
  static double fixed_point(double r) { return 1.0 - 1.0 / r; }
  // False for a degenerate iterate (a fixed point 0 or 1 - 1/r, or outside
  // (0, 1]; NaN too): the run then ends as diverged.
  template <class T>
  static auto usable(T x, T fixed) {
    return (x > lane::splat<T>(0.0)) & (x <= lane::splat<T>(1.0)) & (x != fixed);
  }
  // theta = pi x + branch pi.
  template <class T>
  static T angle(T x, T branch) {
    const T pi = lane::splat<T>(std::numbers::pi);
    return pi * x + branch * pi;
  }
  // Its cosine and sine by sincos.hpp (|theta| <= 3 pi / 2: sincos's exact
  // range, no wrap).
  template <class T>
  static void heading(T x, T branch, T& c, T& s) {
    sincos(angle(x, branch), s, c);
  }

  // The Logistic planner's step in the lanes (kernels/lanes): state x in
  // u.x (u.y becomes NaN after an unusable iterate, which sends the step to
  // the sink), k.a = r, k.b = the branch, k.c = fixed_point(r); the robot
  // moves h_pos = dt_c v along the heading of the new iterate.
  template <class T>
  static SystemStep<T> lane_step(const Vec3<T>& u, const SystemCoeffs<T>& k, T h_pos) {
    const T x = iterate(u.x, k.a);
    T c, s;
    heading(x, k.b, c, s);
    const T zero = lane::splat<T>(0.0);
    const T bad = lane::splat<T>(std::numeric_limits<double>::quiet_NaN());
    return {{x, lane::select(usable(x, k.c), zero, bad), zero}, h_pos * c, h_pos * s};
  }
};

}  // namespace chaosweep
