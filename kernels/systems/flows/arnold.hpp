#pragma once
// The Arnold (ABC) flow (seed 000, Eq. 1) as a listed system, index 0:
//   x' = A sin z + C cos y,  y' = B sin x + A cos z,  z' = C sin y + B cos x.
// Its coefficients are seed 000's A, B, C (the spec's axes, not sys_a..sys_d)
// and its coordinates are angles. It is a carried system (system.hpp): it
// carries its state's sines and cosines from step to step and steps by
// arnold_flow.hpp's RK4 with small-shift stages, and its lanes run
// relabelled so that the heading coordinate is z (to_lane). Its rhs is the
// same field for the shared flow step (flow_rk4_step), which agrees with its
// own step to rounding (tests/kernels/test_kernels_systems.cpp).
#include "kernels/systems/system.hpp"

namespace chaosweep {

struct Arnold {
  static constexpr const char* name = "arnold";
  static constexpr SystemDefaults defaults{0.0, 0.0, 0.0, 0.0, 0, {"", "", "", ""}, {0.0, 1.0, 0.0}};  // spec.md §2
  template <class T>
  static Vec3<T> rhs(const Vec3<T>& u, const SystemCoeffs<T>& k) {
    return arnold_rhs(u, ArnoldCoeffs<T>{k.a, k.b, k.c});
  }

  // Its coordinates are angles: a run starts from its state wrapped into [-pi, pi].
  static Vec3<double> start(const Vec3<double>& u) { return {wrap_pi(u.x), wrap_pi(u.y), wrap_pi(u.z)}; }

  // The carried system's parts (system.hpp, CarriedSystem).
  template <class T>
  static Trig3<T> carry(const Vec3<T>& u) {
    return trig3(u);
  }
  static StepScale<double> scale(const SystemCoeffs<double>& k, double h, double h_pos) {
    return step_scale(ArnoldCoeffs<double>{k.a, k.b, k.c}, h, h_pos);
  }
  static bool small(const SystemCoeffs<double>& k, double h) { return small_shift_mode(h, k.a, k.b, k.c); }
  template <class T, class H>
  static Rk4Step<T> step(const Vec3<T>& u, const Trig3<T>& t, const StepScale<T>& sc, const H& hs,
                         decltype(T() < T()) small) {
    return rk4_step(u, t, sc, hs, small);
  }
  // Two independent vectors' steps interleaved stage by stage (the same
  // operations per lane as step).
  template <bool AllSmall, class T, class H>
  static void step2(Rk4Work<T, H>& a, Rk4Work<T, H>& b, const Trig3<T>& ta, const Trig3<T>& tb, const StepScale<T>& sa,
                    const StepScale<T>& sb, Rk4Step<T>& oa, Rk4Step<T>& ob) {
    rk4_step2<AllSmall>(a, b, ta, tb, sa, sb, oa, ob);
  }
  // The lanes' labels: the heading coordinate ds (1, 2, 3) moved to z, the
  // flow's cyclic symmetry (arnold_flow.hpp, to_lane).
  template <class X>
  static X to_lane(const X& v, int ds) {
    return chaosweep::to_lane(v, ds);
  }
  static SystemCoeffs<double> to_lane(const SystemCoeffs<double>& k, int ds) {
    const Vec3<double> r = chaosweep::to_lane(Vec3<double>{k.a, k.b, k.c}, ds);
    return {r.x, r.y, r.z, k.d};
  }
  template <class X>
  static X from_lane(const X& v, int ds) {
    return chaosweep::from_lane(v, ds);
  }
};

}  // namespace chaosweep
