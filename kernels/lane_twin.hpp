#pragma once
// Twin<V>: two vectors that every operation processes back to back. The
// sincos and RK4 chains are latency-bound; running two independent lanes'
// worth of them in lockstep lets the core overlap them (the "two interleaved
// vectors" of BENCHMARKS.md). Each lane sees exactly the operations of V, so
// results stay bit-identical. Include only from the per-ISA kernel files,
// after simd_lane_math.hpp.
#include <type_traits>

#include "simd_lane_math.hpp"

namespace chaosweep {

template <class T>
struct Twin {
  T a, b;
};

template <class S>
concept Scalar = std::is_arithmetic_v<S>;

#define CW_TWIN_BINARY(op)                                                           \
  template <class T>                                                                 \
  inline auto operator op(const Twin<T>& x, const Twin<T>& y) {                      \
    return Twin<decltype(x.a op y.a)>{x.a op y.a, x.b op y.b};                       \
  }                                                                                  \
  template <class T, Scalar S>                                                       \
  inline auto operator op(const Twin<T>& x, S s) {                                   \
    return Twin<decltype(x.a op s)>{x.a op s, x.b op s};                             \
  }
CW_TWIN_BINARY(+)
CW_TWIN_BINARY(-)
CW_TWIN_BINARY(*)
CW_TWIN_BINARY(&)
CW_TWIN_BINARY(|)
CW_TWIN_BINARY(<)
CW_TWIN_BINARY(>)
CW_TWIN_BINARY(<=)
CW_TWIN_BINARY(>=)
CW_TWIN_BINARY(==)
CW_TWIN_BINARY(!=)
#undef CW_TWIN_BINARY

template <class T>
inline Twin<T> operator-(const Twin<T>& x) {
  return {-x.a, -x.b};
}

namespace lane {

template <class V>
inline Twin<V> fma(const Twin<V>& x, const Twin<V>& y, const Twin<V>& z) {
  return {fma(x.a, y.a, z.a), fma(x.b, y.b, z.b)};
}
template <class V>
inline Twin<V> round_even(const Twin<V>& x) {
  return {round_even(x.a), round_even(x.b)};
}
template <class V>
inline Twin<V> trunc(const Twin<V>& x) {
  return {trunc(x.a), trunc(x.b)};
}
template <class V>
inline auto to_int(const Twin<V>& x) {
  return Twin<decltype(to_int(x.a))>{to_int(x.a), to_int(x.b)};
}
template <class V>
inline void quadrant(const Twin<V>& j, const Twin<V>& sin_r, const Twin<V>& cos_r, Twin<V>& s, Twin<V>& c) {
  quadrant(j.a, sin_r.a, cos_r.a, s.a, c.a);
  quadrant(j.b, sin_r.b, cos_r.b, s.b, c.b);
}
template <class M, class V>
inline Twin<V> select(const Twin<M>& m, const Twin<V>& x, const Twin<V>& y) {
  return {select(m.a, x.a, y.a), select(m.b, x.b, y.b)};
}

#if defined(__AVX2__) && defined(__FMA__)
template <>
inline Twin<v4d> splat<Twin<v4d>>(double v) {
  return {splat<v4d>(v), splat<v4d>(v)};
}
#endif
#if defined(__AVX512F__)
template <>
inline Twin<v8d> splat<Twin<v8d>>(double v) {
  return {splat<v8d>(v), splat<v8d>(v)};
}
#endif

}  // namespace lane
}  // namespace chaosweep
