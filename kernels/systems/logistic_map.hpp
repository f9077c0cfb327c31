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

  // One point of the Logistic planner: the next iterate from x, whether it
  // is usable, and the robot's move h_pos = dt_c v along its heading. The
  // scalar loop (PlannerRun::logistic_loop) and the lanes (lane_step) both
  // take it.
  template <class T>
  struct Step {
    T x;
    decltype(usable(T(), T())) ok;  // int for double (bool & bool), a mask for a vector
    T dX, dY;
  };
  template <class T>
  static Step<T> step(T x, T r, T branch, T fixed, T h_pos) {
    const T next = iterate(x, r);
    T c, s;
    heading(next, branch, c, s);
    return {next, usable(next, fixed), h_pos * c, h_pos * s};
  }

  // The Logistic planner's step in the lanes (kernels/lanes): state x in
  // u.x (u.y becomes NaN after an unusable iterate, which sends the step to
  // the sink), k.a = r, k.b = the branch, k.c = fixed_point(r).
  template <class T>
  static SystemStep<T> lane_step(const Vec3<T>& u, const SystemCoeffs<T>& k, T h_pos) {
    const Step<T> p = step(u.x, k.a, k.b, k.c, h_pos);
    const T zero = lane::splat<T>(0.0);
    const T bad = lane::splat<T>(std::numeric_limits<double>::quiet_NaN());
    return {{p.x, lane::select(p.ok, zero, bad), zero}, p.dX, p.dY};
  }
};

}  // namespace chaosweep
