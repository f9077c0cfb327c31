#pragma once
// The interface every chaotic flow of the planners implements, and the one
// RK4 step they all share. A flow is a struct with
//   static constexpr const char* name;                 // its spec name
//   static constexpr FlowDefaults defaults;            // coefficients, initial state
//   template <class T> static Vec3<T> rhs(const Vec3<T>& u, const FlowCoeffs<T>& k);
// written once over the lane type T (double or a SIMD vector, see
// math/lane_math.hpp), so the scalar reference and every lane width compute
// the same numbers. The robot is coupled to it as to the Arnold flow
// (seed 000, Eq. 3): its heading is the coordinate DSindex picks, the robot
// moves at speed v along it. kernels/systems/flows/ holds the flows;
// system_list.hpp lists them. The Arnold flow keeps its own step
// (arnold_flow.hpp: carried trig, small-shift stages), which this one
// reproduces only to RK4's own error.
#include "kernels/math/lane_math.hpp"
#include "kernels/math/sincos.hpp"
#include "kernels/systems/arnold_flow.hpp"

namespace chaosweep {

// A flow's coefficients, at most four (unused ones are 0).
template <class T>
struct FlowCoeffs {
  T a, b, c, d;
  T at(int k) const { return k == 0 ? a : k == 1 ? b : k == 2 ? c : d; }  // a..d by index
};

struct FlowDefaults {
  double a, b, c, d;
  int count;             // how many of a..d the flow uses
  const char* names[4];  // their names in the literature, for help texts
  double ic[3];          // the initial state (x, y, z) a run takes when ic is unset
  FlowCoeffs<double> coeffs() const { return {a, b, c, d}; }
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

// What one step of a flow gives: the new state and the robot's displacement.
template <class T>
struct FlowStep {
  Vec3<T> u;
  T dX, dY;
};

// The heading's cosine and sine at u. The coordinate is wrapped into
// [-pi, pi] first: sincos.hpp's reduction is exact only for moderate angles,
// and a flow's coordinates (unlike Arnold's) are not angles.
template <class T>
inline void heading_trig(const Vec3<T>& u, const HeadingSelect<T>& h, T& c, T& s) {
  sincos(wrap_pi(heading_coordinate(u, h)), s, c);
}

// Classic RK4 on the 5-state system (x, y, z, X, Y) of flow F: h is the
// flow's step, h_pos the robot's distance per step (f v h, docs/spec.md §2,
// "Scaling factor f"); the robot's displacement is the RK4 mean of the stage
// headings times h_pos, as in rk4_step.
template <class F, class T>
inline FlowStep<T> flow_rk4_step(const Vec3<T>& u, const FlowCoeffs<T>& k, const HeadingSelect<T>& hs, T h, T h_pos) {
  using lane::fma;
  const T half = h * lane::splat<T>(0.5);
  const T two = lane::splat<T>(2.0);
  T c1, s1, c2, s2, c3, s3, c4, s4;
  const Vec3<T> k1 = F::rhs(u, k);
  heading_trig(u, hs, c1, s1);
  const Vec3<T> u2{fma(half, k1.x, u.x), fma(half, k1.y, u.y), fma(half, k1.z, u.z)};
  const Vec3<T> k2 = F::rhs(u2, k);
  heading_trig(u2, hs, c2, s2);
  const Vec3<T> u3{fma(half, k2.x, u.x), fma(half, k2.y, u.y), fma(half, k2.z, u.z)};
  const Vec3<T> k3 = F::rhs(u3, k);
  heading_trig(u3, hs, c3, s3);
  const Vec3<T> u4{fma(h, k3.x, u.x), fma(h, k3.y, u.y), fma(h, k3.z, u.z)};
  const Vec3<T> k4 = F::rhs(u4, k);
  heading_trig(u4, hs, c4, s4);
  const T h6 = h * lane::splat<T>(1.0 / 6.0), pos6 = h_pos * lane::splat<T>(1.0 / 6.0);
  FlowStep<T> out;
  out.u.x = fma(h6, fma(two, k2.x + k3.x, k1.x + k4.x), u.x);
  out.u.y = fma(h6, fma(two, k2.y + k3.y, k1.y + k4.y), u.y);
  out.u.z = fma(h6, fma(two, k2.z + k3.z, k1.z + k4.z), u.z);
  out.dX = pos6 * fma(two, c2 + c3, c1 + c4);
  out.dY = pos6 * fma(two, s2 + s3, s1 + s4);
  return out;
}

}  // namespace chaosweep
