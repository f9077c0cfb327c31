#pragma once
// What a chaotic flow is, and the one RK4 step every flow shares. A flow is
// a struct with
//   static constexpr const char* name;                   // its spec name
//   static constexpr SystemDefaults defaults;            // coefficients, initial state
//   template <class T> static Vec3<T> rhs(const Vec3<T>& u, const SystemCoeffs<T>& k);
// The robot is coupled to it as to the Arnold flow (seed 000, Eq. 3): its
// heading is the coordinate DSindex picks, the robot moves at speed v along
// it. kernels/systems/flows/ holds the flows. The Arnold flow, a carried
// system (system.hpp), brings its own step (arnold_flow.hpp: carried trig,
// small-shift stages), the same RK4 step as this one to rounding, in other
// operations (so not bit for bit).
#include "kernels/systems/system.hpp"

namespace chaosweep {

// Classic RK4 on the 5-state system (x, y, z, X, Y) of flow F: h is the
// flow's step, h_pos the robot's distance per step (f v h, docs/spec.md §2,
// "Scaling factor f"); the robot's displacement is the RK4 mean of the stage
// headings times h_pos, as in rk4_step.
template <class F, class T>
inline SystemStep<T> flow_rk4_step(const Vec3<T>& u, const SystemCoeffs<T>& k, const HeadingSelect<T>& hs, T h,
                                   T h_pos) {
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
  SystemStep<T> out;
  out.u.x = fma(h6, fma(two, k2.x + k3.x, k1.x + k4.x), u.x);
  out.u.y = fma(h6, fma(two, k2.y + k3.y, k1.y + k4.y), u.y);
  out.u.z = fma(h6, fma(two, k2.z + k3.z, k1.z + k4.z), u.z);
  out.dX = pos6 * fma(two, c2 + c3, c1 + c4);
  out.dY = pos6 * fma(two, s2 + s3, s1 + s4);
  return out;
}

}  // namespace chaosweep
