#pragma once
// Elementary lane operations the kernels are written against.
//
// Every numeric kernel is a template over a lane type T. This header gives the
// scalar (width 1) overloads; SIMD widths add overloads with the same names and
// the *same* operation sequence, which is what makes results bit-identical
// across widths (see BENCHMARKS.md / docs/spec.md decisions). Keep each helper a single,
// fixed sequence of IEEE operations: no library calls whose rounding may differ.
#include <cmath>
#include <cstdint>

namespace chaosweep::lane {

using mask1 = bool;
using int1 = std::int64_t;

template <class T>
inline T splat(double v);
template <>
inline double splat<double>(double v) {
  return v;
}

inline double fma(double a, double b, double c) { return std::fma(a, b, c); }

// Round to nearest, ties to even, by the 1.5*2^52 trick: two IEEE additions,
// identical in every width. Valid for |x| < 2^51, far above what callers pass.
inline double round_even(double x) {
  constexpr double magic = 0x1.8p52;
  // Without -ffast-math the compiler may not fold (x + m) - m.
  return (x + magic) - magic;
}

inline double floor(double x) {
  const double r = round_even(x);
  return r > x ? r - 1.0 : r;
}

inline double select(mask1 m, double a, double b) { return m ? a : b; }
inline double trunc(double x) { return std::trunc(x); }
inline bool all(mask1 m) { return m; }
inline bool none(mask1 m) { return !m; }
// One bit per lane, lane 0 in bit 0.
inline unsigned bits(mask1 m) { return m ? 1u : 0u; }

inline int1 to_int(double x) { return static_cast<int1>(x); }
inline double abs(double x) { return std::fabs(x); }
inline double min(double a, double b) { return a < b ? a : b; }
inline double max(double a, double b) { return a > b ? a : b; }

// sin and cos of x = j*pi/2 + r from sin r and cos r: quadrant q = j mod 4
// swaps them (q odd) and sets their signs. Vector widths implement the same
// selection with mask instructions (simd_lane_math.hpp).
template <class T>
inline void quadrant(T j, T sin_r, T cos_r, T& s, T& c) {
  const auto q = to_int(j);
  const auto swap = (q & 1) != 0;
  const T s_abs = select(swap, cos_r, sin_r);
  const T c_abs = select(swap, sin_r, cos_r);
  s = select((q & 2) != 0, -s_abs, s_abs);
  c = select(((q + 1) & 2) != 0, -c_abs, c_abs);
}

}  // namespace chaosweep::lane
