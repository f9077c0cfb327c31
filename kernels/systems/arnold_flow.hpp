#pragma once
// The Arnold (ABC) flow coupled to a unicycle robot (seed 000, Eqs. 1-3), and
// one RK4 step of the 5-state system (x, y, z, X, Y). Templates over the lane
// type so the scalar reference and the SIMD kernels share one arithmetic path.
#include <algorithm>
#include <cmath>

#include "kernels/math/lane_math.hpp"
#include "kernels/math/sincos.hpp"

namespace chaosweep {

template <class T>
struct ArnoldCoeffs {
  T A, B, C;
};

template <class T>
struct Vec3 {
  T x, y, z;
};
template <class T>
inline Vec3<T> operator+(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
inline Vec3<T> operator-(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

// Sines and cosines of the three Arnold coordinates: the right-hand side and the
// heading both come from these, so each RK4 stage needs exactly three sincos.
template <class T>
struct Trig3 {
  T sx, cx, sy, cy, sz, cz;
};

template <class T>
inline Trig3<T> trig3(const Vec3<T>& u) {
  Trig3<T> t;
  sincos(u.x, t.sx, t.cx);
  sincos(u.y, t.sy, t.cy);
  sincos(u.z, t.sz, t.cz);
  return t;
}

// x' = A sin z + C cos y,  y' = B sin x + A cos z,  z' = C sin y + B cos x.
template <class T>
inline Vec3<T> arnold_rhs(const Trig3<T>& t, const ArnoldCoeffs<T>& k) {
  using lane::fma;
  return {fma(k.A, t.sz, k.C * t.cy), fma(k.B, t.sx, k.A * t.cz), fma(k.C, t.sy, k.B * t.cx)};
}

template <class T>
inline Vec3<T> arnold_rhs(const Vec3<T>& u, const ArnoldCoeffs<T>& k) {
  return arnold_rhs(trig3(u), k);
}

// Stages 2-4 of an RK4 step are the base state u shifted by K1, K2 and 2 K3
// (K = (h/2) k, see rk4_step). When the shifts are small, their sines and
// cosines come by angle addition and short Taylor polynomials instead of
// full sincos, each stage from the previous one: stage 2 = stage 1 + K1,
// stage 3 = stage 2 + (K2 - K1), stage 4 = stage 3 + (2 K3 - K2). The mode
// holds when h M <= small_shift, M = max(|A|+|C|, |B|+|A|, |C|+|B|); as M
// bounds |k| and is a Lipschitz constant of k in the max norm, then
//   |K1| <= hM/2 <= 0.1,  |K2 - K1| <= (hM/2) |K1| <= 0.01,
//   |K3 - K2| <= (hM/2) |K2 - K1| <= 0.001,  |2 K3 - K2| <= 0.101,
// so two polynomial lengths serve (ShiftForm). A run's mode is a function of
// its parameters only, so every width computes a lane alike.
//   The next step's stage 1 comes the same way (its trig is carried, see
// rk4_step): u_next = u + (K1 + 2 K2 + 2 K3 + K4) / 3 is stage 4 shifted by
// d = (K1 + 2 K2 - 4 K3 + K4) / 3, which is O(L^3), L = hM/2 <= 0.1: with
// J = (h/2) Dk(u) and Taylor remainders R_i, |R(v)| <= L |v|^2 / 2 (L also
// bounds (h/2) D2k, each component being two sines of one coordinate each),
// K2 = K1 + J K1 + R1, K3 = K1 + J K2 + R2, K4 = K1 + 2 J K3 + R4, so
//   3 d = 2 J ((K1 - K2) + (K3 - K2)) + 2 R1 - 4 R2 + R4,
//   |3 d| <= 2 L (L^2 + L^3) + L^3 + 2 L^3 + 2 L^3 = 7 L^3 + 2 L^4,
//   |d| <= 0.0024  (the carry form).
inline constexpr double small_shift = 0.2;

inline bool small_shift_mode(double h, double A, double B, double C) {
  const double a = std::fabs(A), b = std::fabs(B), c = std::fabs(C);
  return h * std::max({a + c, b + a, c + b}) <= small_shift;
}

// Polynomial lengths, each exact to below 1e-18 up to its bound: carry
// |d| <= 0.0025 (Taylor to d^5 / d^4), tiny |d| <= 0.01 (to d^5 / d^6),
// short |d| <= 0.11 (to d^9; cos d - 1 by a minimax fit, see below).
enum class ShiftForm { carry, tiny, short_ };
inline constexpr double shift_bound(ShiftForm f) {
  return f == ShiftForm::carry ? 0.0025 : f == ShiftForm::tiny ? 0.01 : 0.11;
}

// sin(u + d), cos(u + d) from su = sin u, cu = cos u, as
// su + (su (cos d - 1) + cu sin d): the correction is formed apart from the
// leading term, which keeps the error near 1 ulp.
template <ShiftForm F, class T>
inline void sincos_shift(T su, T cu, T d, T& s, T& c) {
  using lane::fma;
  using lane::splat;
  const T d2 = d * d;
  T ps, pc;
  if constexpr (F == ShiftForm::carry) {
    ps = fma(d2, splat<T>(1.0 / 120.0), splat<T>(-1.0 / 6.0));
    pc = splat<T>(1.0 / 24.0);  // d^6 / 720 < 4e-19
  } else if constexpr (F == ShiftForm::tiny) {
    ps = fma(d2, splat<T>(1.0 / 120.0), splat<T>(-1.0 / 6.0));
    pc = fma(d2, splat<T>(-1.0 / 720.0), splat<T>(1.0 / 24.0));
  } else {
    ps = fma(d2, splat<T>(1.0 / 362880.0), splat<T>(-1.0 / 5040.0));
    ps = fma(ps, d2, splat<T>(1.0 / 120.0));
    ps = fma(ps, d2, splat<T>(-1.0 / 6.0));
    // Remez (weight d^4) on |d| <= 0.11: error 8e-19 with a term fewer than
    // Taylor's (7e-17 to d^8).
    pc = fma(d2, splat<T>(2.4796075379955032e-05), splat<T>(-0.0013888888620835391));
    pc = fma(pc, d2, splat<T>(1.0 / 24.0));
  }
  const T sd = fma(d * d2, ps, d);                // sin d
  const T cm = d2 * fma(pc, d2, splat<T>(-0.5));  // cos d - 1
  s = fma(su, cm, fma(cu, sd, su));
  c = fma(cu, cm, fma(-su, sd, cu));
}

// Trig of base + d by shifting (see sincos_shift), for every lane.
template <ShiftForm F, class T>
inline Trig3<T> trig3_shift(const Trig3<T>& base, const Vec3<T>& d) {
  Trig3<T> t;
  sincos_shift<F>(base.sx, base.cx, d.x, t.sx, t.cx);
  sincos_shift<F>(base.sy, base.cy, d.y, t.sy, t.cy);
  sincos_shift<F>(base.sz, base.cz, d.z, t.sz, t.cz);
  return t;
}

// Trig of the stage point p = (base point) + d: by shifting `base` when
// `small` holds for every lane, by full sincos of p when for none, and lane
// by lane otherwise.
template <ShiftForm F, class T, class M>
inline Trig3<T> trig3_stage(const Trig3<T>& base, const Vec3<T>& d, const Vec3<T>& p, M small) {
  if (lane::all(small)) return trig3_shift<F>(base, d);
  if (lane::none(small)) return trig3(p);
  const Trig3<T> a = trig3_shift<F>(base, d), b = trig3(p);
  return {lane::select(small, a.sx, b.sx), lane::select(small, a.cx, b.cx), lane::select(small, a.sy, b.sy),
          lane::select(small, a.cy, b.cy), lane::select(small, a.sz, b.sz), lane::select(small, a.cz, b.cz)};
}

// trig3_stage, or trig3_shift alone when the caller knows every lane is in
// small-shift mode (AllSmall): the same result for such lanes, no branches.
template <bool AllSmall, ShiftForm F, class T, class M>
inline Trig3<T> trig3_stage_as(const Trig3<T>& base, const Vec3<T>& d, const Vec3<T>& p, M small) {
  if constexpr (AllSmall) return trig3_shift<F>(base, d);
  else return trig3_stage<F>(base, d, p, small);
}

// Which Arnold coordinate drives the heading (DSindex 1=x, 2=y, 3=z), as lane
// masks so lanes may differ.
template <class T>
struct HeadingSelect {
  decltype(T() < T()) is_x, is_y;
};

inline HeadingSelect<double> heading_select(int ds_index) { return {ds_index == 1, ds_index == 2}; }

template <class T>
inline T heading_cos(const Trig3<T>& t, const HeadingSelect<T>& h) {
  return lane::select(h.is_x, t.cx, lane::select(h.is_y, t.cy, t.cz));
}
template <class T>
inline T heading_sin(const Trig3<T>& t, const HeadingSelect<T>& h) {
  return lane::select(h.is_x, t.sx, lane::select(h.is_y, t.sy, t.sz));
}

// The heading is z: for lanes, whose runs are relabelled so that their
// DSindex coordinate sits in z (to_lane below) and need no selection.
struct HeadingZ {};
template <class T>
inline T heading_cos(const Trig3<T>& t, HeadingZ) {
  return t.cz;
}
template <class T>
inline T heading_sin(const Trig3<T>& t, HeadingZ) {
  return t.sz;
}

// The ABC flow is invariant under the cyclic relabelling (x, y, z; A, B, C)
// -> (y, z, x; B, C, A): each component's formula in arnold_rhs becomes the
// next one's, operation for operation, and rk4_step treats the coordinates
// alike, so a relabelled run computes the same numbers. to_lane relabels a
// run with heading ds (1=x, 2=y, 3=z) so that its heading sits in z;
// from_lane undoes it.
template <class T>
inline Vec3<T> to_lane(const Vec3<T>& v, int ds) {
  return ds == 1 ? Vec3<T>{v.y, v.z, v.x} : ds == 2 ? Vec3<T>{v.z, v.x, v.y} : v;
}
template <class T>
inline Vec3<T> from_lane(const Vec3<T>& v, int ds) {
  return ds == 1 ? Vec3<T>{v.z, v.x, v.y} : ds == 2 ? Vec3<T>{v.y, v.z, v.x} : v;
}
template <class T>
inline ArnoldCoeffs<T> to_lane(const ArnoldCoeffs<T>& k, int ds) {
  const Vec3<T> r = to_lane(Vec3<T>{k.A, k.B, k.C}, ds);
  return {r.x, r.y, r.z};
}
template <class T>
inline Trig3<T> to_lane(const Trig3<T>& t, int ds) {
  const Vec3<T> s = to_lane(Vec3<T>{t.sx, t.sy, t.sz}, ds), c = to_lane(Vec3<T>{t.cx, t.cy, t.cz}, ds);
  return {s.x, c.x, s.y, c.y, s.z, c.z};
}
template <class T>
inline Trig3<T> from_lane(const Trig3<T>& t, int ds) {
  const Vec3<T> s = from_lane(Vec3<T>{t.sx, t.sy, t.sz}, ds), c = from_lane(Vec3<T>{t.cx, t.cy, t.cz}, ds);
  return {s.x, c.x, s.y, c.y, s.z, c.z};
}

// Result of one RK4 step: the new (wrapped) Arnold state, its trig (the next
// step's stage 1) and the robot's displacement. The robot's equations depend
// on the heading only, so its displacement is the RK4 weighted mean of the
// stage headings times h_pos.
template <class T>
struct Rk4Step {
  Vec3<T> u;
  Trig3<T> t;
  T dX, dY;
};

// One RK4 step split into its stages, so a kernel may interleave the stages
// of independent vectors (rk4_step2); rk4_step runs them in order. The
// operations per lane are the same either way. H: HeadingSelect<T> or HeadingZ.
template <class T, class H>
struct Rk4Work {
  Vec3<T> u;
  ArnoldCoeffs<T> kh;
  H hs;
  decltype(T() < T()) small;
  Trig3<T> t;  // the current stage's trig
  Vec3<T> K1, K2, K33;
  T c1, s1, c2, s2;
};

// A step's constants, fixed for a run: the coefficients in units of h/2
// (K = (h/2) k) and a sixth of the robot's distance per step.
template <class T>
struct StepScale {
  ArnoldCoeffs<T> kh;
  T pos6;
};

template <class T>
inline StepScale<T> step_scale(const ArnoldCoeffs<T>& k, T h, T h_pos) {
  const T half = h * lane::splat<T>(0.5);
  return {{half * k.A, half * k.B, half * k.C}, h_pos * lane::splat<T>(1.0 / 6.0)};
}

template <bool AllSmall, class T, class H>
inline void rk4_stage1(Rk4Work<T, H>& w, const Trig3<T>& t1, const ArnoldCoeffs<T>& kh) {
  w.kh = kh;
  w.K1 = arnold_rhs(t1, w.kh);
  w.c1 = heading_cos(t1, w.hs);
  w.s1 = heading_sin(t1, w.hs);
  w.t = trig3_stage_as<AllSmall, ShiftForm::short_>(t1, w.K1, w.u + w.K1, w.small);
}

template <bool AllSmall, class T, class H>
inline void rk4_stage2(Rk4Work<T, H>& w) {
  w.K2 = arnold_rhs(w.t, w.kh);
  w.c2 = heading_cos(w.t, w.hs);
  w.s2 = heading_sin(w.t, w.hs);
  w.t = trig3_stage_as<AllSmall, ShiftForm::tiny>(w.t, w.K2 - w.K1, w.u + w.K2, w.small);
}

template <bool AllSmall, class T, class H>
inline void rk4_stage3(Rk4Work<T, H>& w) {
  const Vec3<T> K3 = arnold_rhs(w.t, w.kh);
  w.c2 = w.c2 + heading_cos(w.t, w.hs);  // c23
  w.s2 = w.s2 + heading_sin(w.t, w.hs);  // s23
  const Vec3<T> K23 = w.K2 + K3;
  w.K33 = K3 + K3;
  w.t = trig3_stage_as<AllSmall, ShiftForm::short_>(w.t, w.K33 - w.K2, w.u + w.K33, w.small);
  w.K2 = K23;
}

template <bool AllSmall, class T, class H>
inline Rk4Step<T> rk4_stage4(Rk4Work<T, H>& w, T pos6) {
  using lane::fma;
  const T two = lane::splat<T>(2.0);
  const Vec3<T> K4 = arnold_rhs(w.t, w.kh);
  const T c14 = w.c1 + heading_cos(w.t, w.hs), s14 = w.s1 + heading_sin(w.t, w.hs);
  const Vec3<T>& K1 = w.K1;
  const Vec3<T>& K23 = w.K2;
  const Vec3<T>& K33 = w.K33;
  const Vec3<T>& u = w.u;
  // u + h/6 (k1 + 2 k2 + 2 k3 + k4) = u + (K1 + 2 K2 + 2 K3 + K4) / 3; the
  // same sum less 2 K3 is the shift from stage 4 to it (wrapping is by 2 pi).
  const T third = lane::splat<T>(1.0 / 3.0);
  const Vec3<T> S{fma(two, K23.x, K1.x + K4.x), fma(two, K23.y, K1.y + K4.y), fma(two, K23.z, K1.z + K4.z)};
  Rk4Step<T> out;
  out.u.x = wrap_pi(fma(third, S.x, u.x));
  out.u.y = wrap_pi(fma(third, S.y, u.y));
  out.u.z = wrap_pi(fma(third, S.z, u.z));
  const Vec3<T> d{fma(third, S.x, -K33.x), fma(third, S.y, -K33.y), fma(third, S.z, -K33.z)};
  out.t = trig3_stage_as<AllSmall, ShiftForm::carry>(w.t, d, out.u, w.small);
  out.dX = pos6 * fma(two, w.c2, c14);
  out.dY = pos6 * fma(two, w.s2, s14);
  return out;
}

// h: step of the Arnold system; h_pos: robot distance per step (f * v * h),
// which is how the scaling factor f enters (docs/spec.md §2, "Scaling factor f").
// `small`: the lane runs in small-shift mode (see small_shift_mode).
// t1: the trig of u, carried from the previous step (Rk4Step::t) or trig3(u)
// at a run's start. In small-shift mode a step takes no full sincos at all:
// the carried trig drifts from u's by rounding only (< 7e-12 over 10^6
// steps, tests/test_kernels.cpp; a run re-takes it at every segment start),
// far below RK4's local error (~1e-9 per step at h = 0.1).
//   The stage derivatives are taken in units of h/2 (K = (h/2) k, from the
// coefficients scaled once), so stages 2, 3 and 4 sit at u + K1, u + K2 and
// u + 2 K3 (doubling is exact) with no further products. Each stage's trig is
// reduced at once to what later stages need (its K and heading), and stages
// 1+4 and 2+3 are summed as they come: this keeps few vectors live. The
// operations are the same in every width. The lanes keep each run's
// step_scale and call this form; the next one computes it first (the same
// numbers, bit for bit).
template <class T, class H>
inline Rk4Step<T> rk4_step(const Vec3<T>& u, const Trig3<T>& t1, const StepScale<T>& sc, const H& hs,
                           decltype(T() < T()) small) {
  Rk4Work<T, H> w;
  w.u = u;
  w.hs = hs;
  w.small = small;
  rk4_stage1<false>(w, t1, sc.kh);
  rk4_stage2<false>(w);
  rk4_stage3<false>(w);
  return rk4_stage4<false>(w, sc.pos6);
}

template <class T, class H>
inline Rk4Step<T> rk4_step(const Vec3<T>& u, const Trig3<T>& t1, const ArnoldCoeffs<T>& k, const H& hs, T h, T h_pos,
                           decltype(T() < T()) small) {
  return rk4_step<T, H>(u, t1, step_scale(k, h, h_pos), hs, small);
}

// Two independent steps (w[i] holding u, hs and small, as rk4_step sets
// them), stage by stage in turn, so their dependency chains overlap. Each
// lane's operations are rk4_step's. AllSmall: every lane of both is in
// small-shift mode.
template <bool AllSmall, class T, class H>
inline void rk4_step2(Rk4Work<T, H>& a, Rk4Work<T, H>& b, const Trig3<T>& ta, const Trig3<T>& tb,
                      const StepScale<T>& sa, const StepScale<T>& sb, Rk4Step<T>& oa, Rk4Step<T>& ob) {
  rk4_stage1<AllSmall>(a, ta, sa.kh);
  rk4_stage1<AllSmall>(b, tb, sb.kh);
  rk4_stage2<AllSmall>(a);
  rk4_stage2<AllSmall>(b);
  rk4_stage3<AllSmall>(a);
  rk4_stage3<AllSmall>(b);
  oa = rk4_stage4<AllSmall>(a, sa.pos6);
  ob = rk4_stage4<AllSmall>(b, sb.pos6);
}

// A step from u alone (no carried trig), as at a run's start.
template <class T>
inline Rk4Step<T> rk4_step(const Vec3<T>& u, const ArnoldCoeffs<T>& k, const HeadingSelect<T>& hs, T h, T h_pos,
                           decltype(T() < T()) small) {
  return rk4_step<T, HeadingSelect<T>>(u, trig3(u), k, hs, h, h_pos, small);
}

// Scalar conveniences: the mode from the run's own parameters.
inline Rk4Step<double> rk4_step(const Vec3<double>& u, const Trig3<double>& t, const ArnoldCoeffs<double>& k,
                                const HeadingSelect<double>& hs, double h, double h_pos) {
  return rk4_step<double, HeadingSelect<double>>(u, t, k, hs, h, h_pos, small_shift_mode(h, k.A, k.B, k.C));
}
inline Rk4Step<double> rk4_step(const Vec3<double>& u, const ArnoldCoeffs<double>& k, const HeadingSelect<double>& hs,
                                double h, double h_pos) {
  return rk4_step(u, trig3(u), k, hs, h, h_pos);
}

}  // namespace chaosweep
