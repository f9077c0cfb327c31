// The planners' fast paths of issue 20 give the very bits of what they
// replace: the AVX2 trig3 of the contraction planner
// (kernels/planners/contraction/trig3_fast.hpp).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "kernels/math/splitmix.hpp"
#include "kernels/planners/contraction/trig3_fast.hpp"

using namespace chaosweep;

namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }
double pm1(std::uint64_t& s) { return 2.0 * uniform01(s) - 1.0; }

}  // namespace

// sincos<v4d> lane by lane is sincos<double>: the same trig3 from either.
TEST(FastPaths, Trig3Avx2IsTheScalarTrig3BitForBit) {
  if (!trig3_avx2_usable()) GTEST_SKIP() << "this CPU has no AVX2/FMA";
  std::uint64_t s = 3;
  for (int k = 0; k < 100000; ++k) {
    const double r = k % 5 ? 3.2 : 40.0;  // the wrapped range, and beyond it
    const Vec3<double> u{r * pm1(s), r * pm1(s), r * pm1(s)};
    const Trig3<double> a = trig3(u), b = trig3_fast(u, true);
    ASSERT_EQ(bits(a.sx), bits(b.sx));
    ASSERT_EQ(bits(a.cx), bits(b.cx));
    ASSERT_EQ(bits(a.sy), bits(b.sy));
    ASSERT_EQ(bits(a.cy), bits(b.cy));
    ASSERT_EQ(bits(a.sz), bits(b.sz));
    ASSERT_EQ(bits(a.cz), bits(b.cz));
  }
}
