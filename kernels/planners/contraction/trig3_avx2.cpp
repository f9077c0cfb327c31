// Width 4 sincos for trig3_fast; this file alone in the folder is compiled
// with -march=x86-64-v3. It defines nothing but vector-typed templates and its
// own entry point (tests/check_simd_symbols.sh), so no baseline code can
// link to an AVX2 copy of a shared inline function.
#include "kernels/math/simd_lane_math.hpp"

#include "kernels/math/sincos.hpp"

namespace chaosweep {

void sincos4_avx2(const double in[4], double s[4], double c[4]) {
  lane::v4d x = lane::v4d(_mm256_loadu_pd(in)), vs, vc;
  sincos(x, vs, vc);
  _mm256_storeu_pd(s, __m256d(vs));
  _mm256_storeu_pd(c, __m256d(vc));
}

void wrap_sincos4_avx2(const double in[4], double wrapped[4], double s[4], double c[4]) {
  const lane::v4d x = wrap_pi(lane::v4d(_mm256_loadu_pd(in)));
  lane::v4d vs, vc;
  sincos(x, vs, vc);
  _mm256_storeu_pd(wrapped, __m256d(x));
  _mm256_storeu_pd(s, __m256d(vs));
  _mm256_storeu_pd(c, __m256d(vc));
}

}  // namespace chaosweep
