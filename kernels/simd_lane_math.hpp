#pragma once
// lane_math.hpp's operations for GCC/x86 vector types, with the same IEEE
// operation sequence as the scalar versions (bit-identical results). Only the
// per-ISA kernel files include this, each compiled for its own -march.
#include <immintrin.h>

#include "lane_math.hpp"

namespace chaosweep::lane {

#if defined(__AVX2__) && defined(__FMA__)
using v4d = __m256d;
using v4l = decltype(v4d{} < v4d{});  // the mask type comparisons yield
template <>
inline v4d splat<v4d>(double v) { return _mm256_set1_pd(v); }
inline v4d fma(v4d a, v4d b, v4d c) { return _mm256_fmadd_pd(a, b, c); }
inline v4d round_even(v4d x) {
  const v4d magic = splat<v4d>(0x1.8p52);
  return (x + magic) - magic;
}
template <class M>
inline v4d select(M m, v4d a, v4d b) {
  return m ? a : b;
}
inline v4l to_int(v4d x) { return __builtin_convertvector(x, v4l); }
// Sign flips as XOR of bit 1 of q (and of q + 1) moved to the sign bit.
inline void quadrant(v4d j, v4d sin_r, v4d cos_r, v4d& s, v4d& c) {
  const v4l qi = to_int(j);
  const v4l one = {1, 1, 1, 1};
  const v4l sign = {(long long)0x8000000000000000ULL, (long long)0x8000000000000000ULL,
                    (long long)0x8000000000000000ULL, (long long)0x8000000000000000ULL};
  const v4l swap = (qi & one) != 0;
  const v4d s_abs = select(swap, cos_r, sin_r), c_abs = select(swap, sin_r, cos_r);
  s = _mm256_xor_pd(s_abs, _mm256_castsi256_pd(__m256i((qi << 62) & sign)));
  c = _mm256_xor_pd(c_abs, _mm256_castsi256_pd(__m256i(((qi + one) << 62) & sign)));
}
inline v4d trunc(v4d x) { return _mm256_round_pd(x, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC); }
#endif

#if defined(__AVX512F__)
using v8d = __m512d;
using v8l = decltype(v8d{} < v8d{});
template <>
inline v8d splat<v8d>(double v) { return _mm512_set1_pd(v); }
inline v8d fma(v8d a, v8d b, v8d c) { return _mm512_fmadd_pd(a, b, c); }
inline v8d round_even(v8d x) {
  const v8d magic = splat<v8d>(0x1.8p52);
  return (x + magic) - magic;
}
template <class M>
inline v8d select(M m, v8d a, v8d b) {
  return m ? a : b;
}
inline v8l to_int(v8d x) { return __builtin_convertvector(x, v8l); }
inline void quadrant(v8d j, v8d sin_r, v8d cos_r, v8d& s, v8d& c) {
  const __m512i qi = _mm512_cvttpd_epi64(j);
  const __mmask8 swap = _mm512_test_epi64_mask(qi, _mm512_set1_epi64(1));
  const v8d s_abs = _mm512_mask_blend_pd(swap, sin_r, cos_r);
  const v8d c_abs = _mm512_mask_blend_pd(swap, cos_r, sin_r);
  const __m512i sign = _mm512_set1_epi64((long long)0x8000000000000000ULL);
  s = _mm512_xor_pd(s_abs, _mm512_castsi512_pd(_mm512_and_si512(_mm512_slli_epi64(qi, 62), sign)));
  const __m512i q1 = _mm512_add_epi64(qi, _mm512_set1_epi64(1));
  c = _mm512_xor_pd(c_abs, _mm512_castsi512_pd(_mm512_and_si512(_mm512_slli_epi64(q1, 62), sign)));
}
inline v8d trunc(v8d x) { return _mm512_mask_roundscale_pd(x, 0xFF, x, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC); }
#endif

}  // namespace chaosweep::lane
