#pragma once
// Keeping the robot inside the workspace (docs/spec.md §2, "Boundary and obstacle handling").
#include "kernels/math/lane_math.hpp"

namespace chaosweep {

// Reflect u into [lo, hi] as often as needed: a triangle wave of period
// 2*(hi - lo). Values already inside are returned unchanged, bit for bit, and
// a single reflection is computed exactly as 2*lo - u or 2*hi - u (Eq. 7);
// only overshoots longer than the band take the general (periodic) path.
template <class T>
inline T triangle_fold(T u, T lo, T hi) {
  T r = lane::select(u < lo, (lo + lo) - u, u);
  r = lane::select(r > hi, (hi + hi) - r, r);
  // The common case, every lane inside after at most one reflection, skips
  // the periodic path's division (the lanes' obstacle maps take this path
  // at every step); the select below would return r for each such lane.
  const auto inside = (r >= lo) & (r <= hi);
  if (lane::all(inside)) return r;
  const T width = hi - lo;
  const T period = width + width;
  T w = u - lo;
  w = w - period * lane::floor(w / period);
  w = lane::select(w > width, period - w, w);
  return lane::select(inside, r, lo + w);
}

// The scalar form branches on the common case (already inside); same result.
inline double triangle_fold(double u, double lo, double hi) {
  if (u >= lo && u <= hi) return u;
  return triangle_fold<double>(u, lo, hi);
}

// Eq. 7, paper-literal: a position within fo of a wall, or beyond it, is
// reflected about the line at offset fo. Repeated reflection (the fold of the
// band [lo+fo, hi-fo]) equals Eq. 7 for every step shorter than the band and
// still keeps the robot inside when a large f makes steps long.
template <class T>
inline T mirror_eq7(T u, T lo, T hi, T fo) {
  return triangle_fold(u, lo + fo, hi - fo);
}

// Sign of d(fold)/du at u: +1 on rising, -1 on falling stretches of the wave.
// The fold boundary needs it to carry an in-map correction back to the
// unfolded coordinate.
inline double fold_slope(double u, double lo, double hi) {
  const double width = hi - lo;
  const double k = lane::floor((u - lo) / width);
  const double parity = k - 2.0 * lane::floor(k * 0.5);
  return parity == 0.0 ? 1.0 : -1.0;
}

}  // namespace chaosweep
