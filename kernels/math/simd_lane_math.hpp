#pragma once
// lane_math.hpp's operations for GCC/x86 vector types, with the same IEEE
// operation sequence as the scalar versions (bit-identical results). Only the
// per-ISA kernel files include this, each compiled for its own -march.
#include <immintrin.h>

#include "kernels/math/lane_math.hpp"

namespace chaosweep::lane {

#if defined(__AVX2__) && defined(__FMA__)
// Plain GCC vector types (the intrinsics' __m256d/__m512d carry may_alias,
// which templates would drop with a warning); the intrinsics accept them.
using v4d = double __attribute__((vector_size(32)));
using v4l = decltype(v4d{} < v4d{});  // the mask type comparisons yield
template <>
inline v4d splat<v4d>(double v) {
  return _mm256_set1_pd(v);
}
inline v4d fma(v4d a, v4d b, v4d c) { return _mm256_fmadd_pd(a, b, c); }
inline v4d round_even(v4d x) {
  const v4d magic = splat<v4d>(0x1.8p52);
  return (x + magic) - magic;
}
template <class M>
inline v4d select(M m, v4d a, v4d b) {
  return m ? a : b;
}
inline v4d floor(v4d x) {
  const v4d r = round_even(x);
  return select(r > x, r - 1.0, r);
}
inline v4l to_int(v4d x) { return __builtin_convertvector(x, v4l); }
// Sign flips as XOR of bit 1 of q (and of q + 1) moved to the sign bit.
inline void quadrant(v4d j, v4d sin_r, v4d cos_r, v4d& s, v4d& c) {
  const v4l qi = to_int(j);
  const v4l swap = (qi & 1) != 0;
  const v4d s_abs = select(swap, cos_r, sin_r), c_abs = select(swap, sin_r, cos_r);
  const v4l sign_bit = v4l{} + (long long)0x8000000000000000ULL;
  s = v4d(v4l(s_abs) ^ ((qi << 62) & sign_bit));
  c = v4d(v4l(c_abs) ^ (((qi + 1) << 62) & sign_bit));
}
inline bool all(v4l m) { return _mm256_movemask_pd(__m256d(m)) == 0xF; }
inline bool none(v4l m) { return _mm256_movemask_pd(__m256d(m)) == 0; }
inline unsigned bits(v4l m) { return unsigned(_mm256_movemask_pd(__m256d(m))); }
inline v4d trunc(v4d x) { return _mm256_round_pd(x, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC); }
#endif

#if defined(__AVX512F__)
using v8d = double __attribute__((vector_size(64)));
using v8l = decltype(v8d{} < v8d{});
template <>
inline v8d splat<v8d>(double v) {
  return _mm512_set1_pd(v);
}
inline v8d fma(v8d a, v8d b, v8d c) { return _mm512_fmadd_pd(a, b, c); }
inline v8d round_even(v8d x) {
  const v8d magic = splat<v8d>(0x1.8p52);
  return (x + magic) - magic;
}
template <class M>
inline v8d select(M m, v8d a, v8d b) {
  return m ? a : b;
}
inline v8d floor(v8d x) {
  const v8d r = round_even(x);
  return select(r > x, r - 1.0, r);
}
inline v8l to_int(v8d x) { return __builtin_convertvector(x, v8l); }
inline void quadrant(v8d j, v8d sin_r, v8d cos_r, v8d& s, v8d& c) {
  const v8l qi = to_int(j);
  const __mmask8 swap = _mm512_test_epi64_mask(__m512i(qi), _mm512_set1_epi64(1));
  const v8d s_abs = _mm512_mask_blend_pd(swap, sin_r, cos_r);
  const v8d c_abs = _mm512_mask_blend_pd(swap, cos_r, sin_r);
  const v8l sign_bit = v8l{} + (long long)0x8000000000000000ULL;
  s = v8d(v8l(s_abs) ^ ((qi << 62) & sign_bit));
  c = v8d(v8l(c_abs) ^ (((qi + 1) << 62) & sign_bit));
}
inline bool all(v8l m) { return _mm512_movepi64_mask(__m512i(m)) == 0xFF; }
inline bool none(v8l m) { return _mm512_movepi64_mask(__m512i(m)) == 0; }
inline unsigned bits(v8l m) { return unsigned(_mm512_movepi64_mask(__m512i(m))); }
inline v8d trunc(v8d x) { return _mm512_mask_roundscale_pd(x, 0xFF, x, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC); }
#endif

}  // namespace chaosweep::lane
