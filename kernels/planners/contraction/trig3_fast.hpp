#pragma once
// trig3 of one Arnold state, the three sincos in one AVX2 vector when the CPU
// runs it (sincos<v4d> is sincos<double> lane by lane: the same IEEE
// operations, bit-identical), else the portable scalar trig3. The scalar
// sincos calls libm's fma 19 times per angle in a baseline build; seed 003's
// RK2 steps are sequential, so one vector per stage is what batching allows.
#include "kernels/systems/arnold_flow.hpp"

namespace chaosweep {

// in: x, y, z, (unused); out: the sines and cosines of the four lanes.
// Defined in trig3_avx2.cpp, compiled for x86-64-v3; call only when
// trig3_avx2_usable().
void sincos4_avx2(const double in[4], double s[4], double c[4]);
// The same after wrap_pi of each lane (wrapped: the wrapped angles).
void wrap_sincos4_avx2(const double in[4], double wrapped[4], double s[4], double c[4]);
bool trig3_avx2_usable();

inline Trig3<double> trig3_fast(const Vec3<double>& u, bool avx2) {
  if (!avx2) return trig3(u);
  alignas(32) const double in[4] = {u.x, u.y, u.z, 0.0};
  alignas(32) double s[4], c[4];
  sincos4_avx2(in, s, c);
  return {s[0], c[0], s[1], c[1], s[2], c[2]};
}

// u = wrap_pi of each coordinate of `next`, and trig3(u).
inline Trig3<double> wrap_trig3_fast(const Vec3<double>& next, Vec3<double>& u, bool avx2) {
  if (!avx2) {
    u = {wrap_pi(next.x), wrap_pi(next.y), wrap_pi(next.z)};
    return trig3(u);
  }
  alignas(32) const double in[4] = {next.x, next.y, next.z, 0.0};
  alignas(32) double w[4], s[4], c[4];
  wrap_sincos4_avx2(in, w, s, c);
  u = {w[0], w[1], w[2]};
  return {s[0], c[0], s[1], c[1], s[2], c[2]};
}

}  // namespace chaosweep
