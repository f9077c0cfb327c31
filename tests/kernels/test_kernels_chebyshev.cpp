// Kernels: the Chebyshev map's own analysis (docs/spec.md §3, seed 001 Sections
// 2.1-2.3): Lyapunov exponents, orbit histograms, v(xy).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "kernels/planners/chebyshev/chebyshev_analysis.hpp"
#include "kernels/planners/chebyshev/chebyshev_orbit.hpp"
#include "kernels/systems/chebyshev_map.hpp"

using namespace chaosweep;

namespace {

constexpr double pi = std::numbers::pi;
// 99.9% quantile of chi-square with 49 degrees of freedom (50 bins).
constexpr double chi2_49_999 = 85.35;

}  // namespace

// The raw exponent telescopes (ln|f'(x_i)| = ln k + ln sin t_{i+1} - ln sin t_i,
// x = cos t), so its error is O(1/n) and 1e6 steps leave it near 1e-6.
TEST(ChebyshevLyapunov, RawMapAtK6IsLn6) { EXPECT_NEAR(lyapunov_exponent(6, 0.1, 1'000'000), std::log(6.0), 1e-3); }

TEST(ChebyshevLyapunov, ArcsineTransformedMapIsAlsoLn6ByConjugacy) {
  EXPECT_NEAR(lyapunov_exponent_arcsine(6, 0.1, 1'000'000), std::log(6.0), 1e-3);
}

TEST(ChebyshevLyapunov, GrowsLikeLnKForKFrom2To8) {
  for (int k = 2; k <= 8; ++k) {
    EXPECT_NEAR(lyapunov_exponent(k, 0.1, 100'000), std::log(k), 1e-2) << "k = " << k;
    EXPECT_NEAR(lyapunov_exponent_arcsine(k, 0.1, 100'000), std::log(k), 1e-2) << "k = " << k;
  }
}

// Eq. 7 as printed is d(T o f)/dx = (2k/pi)/sin t up to sign: its orbit mean is
// ln(2k/pi) + ln 2 = ln(4k/pi) = 2.0333 at k = 6, not the paper's 3.2147. The
// terms -ln sin t have sd pi/sqrt(12) and lag-L correlation 6^-L, so the mean
// of 1e6 has sd about 1.1e-3; 6e-3 is over five of them.
TEST(ChebyshevLyapunov, PaperEq7AsPrintedAveragesToLn4kOverPi) {
  const double v = lyapunov_paper_eq7(6, 0.1, 1'000'000);
  EXPECT_NEAR(v, std::log(24.0 / pi), 6e-3);
  EXPECT_GT(std::abs(v - 3.2147), 1.0);
}

TEST(ChebyshevLyapunov, OrbitOnTheFixedPointThrowsNamingIt) {
  EXPECT_THROW(lyapunov_exponent(6, 1.0, 10), std::domain_error);
  // f(0) = cos(3 pi) = -1 exactly, then f(-1) = 1 for even k.
  EXPECT_THROW(lyapunov_exponent(6, 0.0, 10, 0), std::domain_error);
  try {
    lyapunov_exponent_arcsine(6, -1.0, 10);
    FAIL() << "no throw";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("step 0"), std::string::npos) << e.what();
  }
}

TEST(ChebyshevLyapunov, BadArgumentsAreInvalid) {
  EXPECT_THROW(lyapunov_exponent(1, 0.1, 10), std::invalid_argument);
  EXPECT_THROW(lyapunov_exponent(6, 1.5, 10), std::invalid_argument);
  EXPECT_THROW(lyapunov_exponent(6, std::nan(""), 10), std::invalid_argument);
  EXPECT_THROW(lyapunov_exponent(6, 0.1, 0), std::invalid_argument);
}

// 2e5 samples, 50 bins: over 38 initial values the flat statistics stayed
// below 73 (critical value 85.35) and the raw-vs-uniform one above 1.1e5.
TEST(ChebyshevHistogram, ArcsineTransformedOrbitIsFlat) {
  const auto h = orbit_histogram(6, 0.1, 200'000, 50, ChebTransform::arcsine);
  EXPECT_LT(chi_square_uniform(h), chi2_49_999);
}

TEST(ChebyshevHistogram, ArccosineTransformedOrbitIsFlatOnZeroTwo) {
  const auto h = orbit_histogram(6, 0.1, 200'000, 50, ChebTransform::arccosine);
  EXPECT_LT(chi_square_uniform(h), chi2_49_999);
}

TEST(ChebyshevHistogram, RawOrbitIsNotFlatButFollowsTheArcsineDensity) {
  const auto h = orbit_histogram(6, 0.1, 200'000, 50, ChebTransform::none);
  EXPECT_GT(chi_square_uniform(h), 100 * chi2_49_999);
  EXPECT_LT(chi_square_arcsine(h), chi2_49_999);
  // Denser at the ends than in the middle, as the paper's Fig. 2 shows.
  EXPECT_GT(h.front(), 3 * h[25]);
  EXPECT_GT(h.back(), 3 * h[24]);
}

TEST(ChebyshevHistogram, CountsEverySampleIncludingX0) {
  long total = 0;
  for (long c : orbit_histogram(6, 0.1, 1234, 7, ChebTransform::none)) total += c;
  EXPECT_EQ(total, 1234);
  EXPECT_EQ(orbit_histogram(6, 0.1, 1, 4, ChebTransform::none)[2], 1);  // 0.1 is in [0, 0.5)
}

TEST(ChebyshevHistogram, ChiSquareIsZeroOnExpectedCounts) {
  EXPECT_DOUBLE_EQ(chi_square_uniform({5, 5, 5, 5}), 0.0);
  EXPECT_DOUBLE_EQ(chi_square_uniform({8, 2}), 3.6);  // (3^2 + 3^2) / 5
  // Two bins over [-1, 1]: the arcsine density puts half its mass in each.
  EXPECT_DOUBLE_EQ(chi_square_arcsine({50, 50}), 0.0);
  EXPECT_THROW(chi_square_uniform({}), std::invalid_argument);
}

// Limits for independent samples: E|X - Y| = 8/pi^2 (arcsine) and 2/3
// (uniform on a range of 2). The samples' sd is 0.586 and 0.471; along the
// orbits the lag correlations are negligible (38 orbit pairs of 1e6 gave sd
// 5.2e-4 and 4.4e-4), so 3e-3 is over five standard errors.
TEST(ChebyshevVariableDifference, OriginalMapTendsTo8OverPiSquared) {
  EXPECT_NEAR(variable_difference(6, 0.1, 0.2, 1'000'000, ChebTransform::none), 8 / (pi * pi), 3e-3);
}

TEST(ChebyshevVariableDifference, ArcsineTransformTendsToTwoThirds) {
  EXPECT_NEAR(variable_difference(6, 0.1, 0.2, 1'000'000, ChebTransform::arcsine), 2.0 / 3.0, 3e-3);
}

// (2/pi) acos x = 1 - (2/pi) asin x, so the differences are the same.
TEST(ChebyshevVariableDifference, ArccosineEqualsArcsine) {
  for (long n : {2000L, 10000L})
    EXPECT_NEAR(variable_difference(6, 0.1, 0.2, n, ChebTransform::arccosine),
                variable_difference(6, 0.1, 0.2, n, ChebTransform::arcsine), 1e-12);
}

TEST(ChebyshevVariableDifference, InitialValuesAreTheFirstSamples) {
  EXPECT_DOUBLE_EQ(variable_difference(6, 0.1, 0.2, 1, ChebTransform::none), 0.1);
  const double x2 = chebyshev_step(0.1, 6), y2 = chebyshev_step(0.2, 6);
  EXPECT_DOUBLE_EQ(variable_difference(6, 0.1, 0.2, 2, ChebTransform::none), (0.1 + std::abs(x2 - y2)) / 2);
}

TEST(ChebyshevVariableDifference, CollapsedOrbitThrows) {
  // f(0.5) = cos(2 pi) = 1: a fixed point.
  EXPECT_THROW(variable_difference(6, 0.1, 0.5, 100, ChebTransform::none), std::domain_error);
}

TEST(ChebyshevMap, StepAtAndBeyondTheEndsStaysFinite) {
  EXPECT_EQ(chebyshev_step(1.0, 6), 1.0);
  EXPECT_EQ(chebyshev_step(-1.0, 6), 1.0);
  EXPECT_EQ(chebyshev_step(-1.0, 5), -1.0);
  EXPECT_EQ(chebyshev_step(1.0 + 1e-12, 6), 1.0);
  EXPECT_EQ(chebyshev_step(std::nextafter(-1.0, -2.0), 5), -1.0);
  for (double x : {1.0, -1.0, 1.0 + 1e-9, -1.0 - 1e-9, 2.0, -2.0})
    for (ChebTransform t : {ChebTransform::none, ChebTransform::arcsine, ChebTransform::arccosine}) {
      const double u = cheb_transform(chebyshev_step(x, 6), t);
      EXPECT_TRUE(std::isfinite(u)) << x;
      EXPECT_GE(u, cheb_lo(t));
      EXPECT_LE(u, cheb_hi(t));
    }
}

// The orbit a run draws, its own first iterates then the shared blocks,
// is the map iterated and transformed one value at a time, across several
// blocks, for runs drawing the same orbit in turns (the second finds the
// first's blocks) and for an orbit that lands on the fixed point 1.
TEST(ChebyshevOrbit, DrawsTheMapsIteratesAndTheirTransformsWhoeverBuiltTheBlocks) {
  const int draws = 20000;  // the own iterates and blocks of 64, 128, ..., 16384
  for (const ChebTransform t : {ChebTransform::none, ChebTransform::arcsine, ChebTransform::arccosine})
    for (const auto& [k, x0] : std::vector<std::pair<int, double>>{{6, 0.123456789}, {3, -0.7}, {6, 0.5}}) {
      const double lo = cheb_lo(t), span = cheb_hi(t) - lo;
      std::vector<ChebyshevOrbit::Value> expected;
      double x = x0;
      for (int n = 1; n <= draws; ++n) {
        x = chebyshev_step(x, k);
        expected.push_back({x, (cheb_transform(x, t) - lo) / span});
      }
      // Two runs out of step (the one first at a block leaves a mark and
      // draws on, the other builds it), then a third that reads the blocks.
      ChebyshevOrbit first(k, x0, t), second(k, x0, t), third(k, x0, t);
      for (int n = 0; n < draws; ++n) {
        ChebyshevOrbit& ahead = n % 3 == 0 ? second : first;
        ChebyshevOrbit& behind = n % 3 == 0 ? first : second;
        for (ChebyshevOrbit* o : {&ahead, &behind}) {
          const ChebyshevOrbit::Value v = o->next();
          ASSERT_EQ(v.x, expected[std::size_t(n)].x) << "k " << k << ", x0 " << x0 << ", n " << n + 1;
          ASSERT_EQ(v.u, expected[std::size_t(n)].u) << "k " << k << ", x0 " << x0 << ", n " << n + 1;
        }
      }
      for (int n = 0; n < draws; ++n) {
        const ChebyshevOrbit::Value v = third.next();
        ASSERT_EQ(v.x, expected[std::size_t(n)].x) << "k " << k << ", x0 " << x0 << ", n " << n + 1 << " (third)";
        ASSERT_EQ(v.u, expected[std::size_t(n)].u) << "k " << k << ", x0 " << x0 << ", n " << n + 1 << " (third)";
      }
    }
}
