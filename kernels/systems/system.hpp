#pragma once
// What every chaotic system driving the seed-000 planner family shares, flow
// (flow.hpp) or map (chaotic_map.hpp): at most four coefficients, their
// defaults and the initial state, and how the robot is coupled to it. Each is
// written once over the lane type T (double or a SIMD vector, see
// math/lane_math.hpp), so the scalar reference and every lane width compute
// the same numbers. system_list.hpp lists the systems and steps any of them.
#include <concepts>

#include "kernels/math/lane_math.hpp"
#include "kernels/math/sincos.hpp"
#include "kernels/systems/arnold_flow.hpp"

namespace chaosweep {

// A system's coefficients, at most four (unused ones are 0).
template <class T>
struct SystemCoeffs {
  T a, b, c, d;
  T at(int k) const { return k == 0 ? a : k == 1 ? b : k == 2 ? c : d; }  // a..d by index
};

struct SystemDefaults {
  double a, b, c, d;
  int count;             // how many of a..d the system uses
  const char* names[4];  // their names in the literature, for help texts
  double ic[3];          // the initial state (x, y, z) a run takes when ic is unset
  SystemCoeffs<double> coeffs() const { return {a, b, c, d}; }
};

// |x| as a select, the same operations in every lane type (so a signed zero
// comes out alike in scalar and vector code).
template <class T>
inline T flow_abs(T x) {
  return lane::select(x < lane::splat<T>(0.0), -x, x);
}

// The heading coordinate of u (HeadingSelect: per-lane masks for x and y,
// else z).
template <class T>
inline T heading_coordinate(const Vec3<T>& u, const HeadingSelect<T>& h) {
  return lane::select(h.is_x, u.x, lane::select(h.is_y, u.y, u.z));
}

// What one step of a system gives: the new state and the robot's displacement.
template <class T>
struct SystemStep {
  Vec3<T> u;
  T dX, dY;
};

// The cosine and sine of a heading angle. It is wrapped into [-pi, pi]
// first: sincos.hpp's reduction is exact only for moderate angles, and a
// flow's or map's coordinates (unlike Arnold's) are not angles.
template <class T>
inline void heading_trig(T angle, T& c, T& s) {
  sincos(wrap_pi(angle), s, c);
}
template <class T>
inline void heading_trig(const Vec3<T>& u, const HeadingSelect<T>& h, T& c, T& s) {
  heading_trig(heading_coordinate(u, h), c, s);
}

// A carried system carries state from one step to the next and brings its
// own step for it, instead of the shared ones (flow_rk4_step, map_step). The
// Arnold flow (flows/arnold.hpp) carries its state's sines and cosines, so
// an RK4 step needs no full sincos. Beside a flow's parts it has
//   template <class T> static Trig3<T> carry(const Vec3<T>& u);   // the carry of a state
//   static StepScale<double> scale(const SystemCoeffs<double>& k, double h, double h_pos);
//   static bool small(const SystemCoeffs<double>& k, double h);   // its step's mode
//   template <class T, class H> static Rk4Step<T> step(u, carry, scale, heading, small);
//   template <bool AllSmall, ...> static void step2(...);          // two vectors interleaved
//   to_lane / from_lane (state, carry, coefficients): the labels its lanes
//   run in, the heading coordinate moved to z (HeadingZ).
// A run takes the carry of its state afresh at its start and at each
// segment's start, so a carry is a pure function of the run. The hooks
// beyond carry are checked where they are used (the lanes, LaneBinding).
template <class F>
concept CarriedSystem = requires(const Vec3<double>& u) {
  { F::carry(u) } -> std::same_as<Trig3<double>>;
};

// The state a run of system F starts from: its initial state as is, or as
// F::start makes it (the Arnold flow's coordinates are angles: wrapped).
template <class F>
inline Vec3<double> system_start(const Vec3<double>& u) {
  if constexpr (requires { F::start(u); }) return F::start(u);
  else return u;
}

}  // namespace chaosweep
