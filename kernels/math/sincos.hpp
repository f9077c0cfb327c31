#pragma once
// Branch-free sine and cosine for any lane type (Cephes polynomials,
// Cody-Waite reduction with FMA), and the angle wrap the kernels apply every
// step. Accurate to ~1 ulp for |x| <= 2^20; the kernels keep |x| <= pi.
#include "kernels/math/lane_math.hpp"

namespace chaosweep {

namespace sincos_detail {
// pi/2 and 2*pi split into three doubles each (exact sum to ~1e-49).
inline constexpr double pio2_1 = 1.5707963267948966;
inline constexpr double pio2_2 = 6.123233995736766e-17;
inline constexpr double pio2_3 = -1.4973849048591698e-33;
inline constexpr double two_over_pi = 0.6366197723675814;
inline constexpr double twopi_1 = 6.283185307179586;
inline constexpr double twopi_2 = 2.4492935982947064e-16;
inline constexpr double inv_twopi = 0.15915494309189535;
// Cephes sin/cos minimax coefficients on [-pi/4, pi/4].
inline constexpr double s0 = 1.58962301576546568060e-10, s1 = -2.50507477628578072866e-8,
                        s2 = 2.75573136213857245213e-6, s3 = -1.98412698295895385996e-4, s4 = 8.33333333332211858878e-3,
                        s5 = -1.66666666666666307295e-1;
inline constexpr double c0 = -1.13585365213876817300e-11, c1 = 2.08757008419747316778e-9,
                        c2 = -2.75573141792967388112e-7, c3 = 2.48015872888517045348e-5,
                        c4 = -1.38888888888730564116e-3, c5 = 4.16666666666665929218e-2;
}  // namespace sincos_detail

template <class T>
inline void sincos(T x, T& s, T& c) {
  using namespace sincos_detail;
  using lane::fma;
  const T j = lane::round_even(x * two_over_pi);
  T r = fma(-j, lane::splat<T>(pio2_1), x);
  r = fma(-j, lane::splat<T>(pio2_2), r);
  r = fma(-j, lane::splat<T>(pio2_3), r);
  const T z = r * r;
  T ps = fma(fma(fma(fma(fma(lane::splat<T>(s0), z, lane::splat<T>(s1)), z, lane::splat<T>(s2)), z, lane::splat<T>(s3)),
                 z, lane::splat<T>(s4)),
             z, lane::splat<T>(s5));
  T pc = fma(fma(fma(fma(fma(lane::splat<T>(c0), z, lane::splat<T>(c1)), z, lane::splat<T>(c2)), z, lane::splat<T>(c3)),
                 z, lane::splat<T>(c4)),
             z, lane::splat<T>(c5));
  const T sin_r = fma(r * z, ps, r);
  const T cos_r = fma(z * z, pc, fma(lane::splat<T>(-0.5), z, lane::splat<T>(1.0)));
  lane::quadrant(j, sin_r, cos_r, s, c);
}

// x - 2*pi*round(x / 2*pi): maps an angle into [-pi, pi] so sincos stays in its
// cheap range. Used on the Arnold state, whose flow is 2*pi-periodic.
template <class T>
inline T wrap_pi(T x) {
  using namespace sincos_detail;
  const T k = lane::round_even(x * inv_twopi);
  T r = lane::fma(-k, lane::splat<T>(twopi_1), x);
  return lane::fma(-k, lane::splat<T>(twopi_2), r);
}

}  // namespace chaosweep
