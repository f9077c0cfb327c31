// Kernels: the numerics of docs/spec.md §1 and §2 (original Arnold planner).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <sstream>

#include "kernels/core/boundary.hpp"
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/metrics.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/core/robot_motion.hpp"
#include "kernels/math/inline_hypot.hpp"
#include "kernels/math/sincos.hpp"
#include "kernels/planners/arnold/transit.hpp"
#include "kernels/planners/planner.hpp"
#include "kernels/systems/arnold_flow.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;
using chaosweep::test::small_run;
using chaosweep::test::square_map;

namespace {

std::set<std::pair<int, int>> marked_cells(const CoverageGrid& g) {
  std::set<std::pair<int, int>> s;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i)
      if (g.at(i, j) == CoverageGrid::visited) s.insert({i, j});
  return s;
}

}  // namespace

// ---------------------------------------------------------------- sincos

namespace {
void expect_sincos_near_libm(double x, double tol) {
  double s, c;
  sincos(x, s, c);
  ASSERT_NEAR(s, std::sin(x), tol) << x;
  ASSERT_NEAR(c, std::cos(x), tol) << x;
}
}  // namespace

TEST(SinCos, MatchesLibmToTwoUlpOnTheWrappedRange) {
  for (int i = -100000; i <= 100000; ++i) expect_sincos_near_libm(std::numbers::pi * i / 100000.0, 2.3e-16);
}

TEST(SinCos, StaysAccurateOutsideTheWrappedRange) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e4, 1e4);
  for (int i = 0; i < 10000; ++i) expect_sincos_near_libm(u(rng), 1e-15);
}

TEST(WrapPi, MapsIntoMinusPiPiAndKeepsTheAngle) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int i = 0; i < 10000; ++i) {
    const double x = u(rng), w = wrap_pi(x);
    ASSERT_LE(std::fabs(w), std::numbers::pi + 1e-12) << x;
    ASSERT_NEAR(std::sin(w), std::sin(x), 1e-12) << x;
    ASSERT_NEAR(std::cos(w), std::cos(x), 1e-12) << x;
  }
  EXPECT_EQ(wrap_pi(1.0), 1.0);  // already inside: untouched
}

// ------------------------------------------------------------ Arnold flow

TEST(ArnoldRhs, IsTheAbcFlow) {
  const ArnoldCoeffs<double> k{0.5, 0.25, 0.25};
  for (const Vec3<double> u : {Vec3<double>{0, 1, 0}, Vec3<double>{0.3, -2.1, 1.7}, Vec3<double>{3, 3, -3}}) {
    const Vec3<double> d = arnold_rhs(u, k);
    EXPECT_NEAR(d.x, 0.5 * std::sin(u.z) + 0.25 * std::cos(u.y), 1e-15);
    EXPECT_NEAR(d.y, 0.25 * std::sin(u.x) + 0.5 * std::cos(u.z), 1e-15);
    EXPECT_NEAR(d.z, 0.25 * std::sin(u.y) + 0.25 * std::cos(u.x), 1e-15);
  }
}

namespace {
// Largest error of sincos_shift<F> over random angles and shifts up to
// `bound`, against long double sinl/cosl of the exact sum.
template <ShiftForm F>
double max_shift_error() {
  const double bound = shift_bound(F);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi), shift(-bound, bound);
  double worst = 0;
  for (int i = 0; i < 100000; ++i) {
    const double a = angle(rng), d = i < 2 ? (i ? -bound : bound) : shift(rng);
    double s, c;
    sincos_shift<F>(std::sin(a), std::cos(a), d, s, c);
    const long double x = (long double)a + d;
    worst = std::max({worst, double(std::fabs(s - sinl(x))), double(std::fabs(c - cosl(x)))});
  }
  return worst;
}
}  // namespace

// ---------------------------------------------------------------- hypot

// The inline hypot returns the C library's bits (glibc 2.35 and later, this
// project's Debian 12 has 2.36): the planners' results stay what they were
// with std::hypot. Random pairs over every scale the scaling branches
// handle, the walks' own differences (a few metres, often one near zero),
// and the edge cases.
TEST(KernelMath, InlineHypotIsTheCLibrarysHypot) {
  const auto same = [](double x, double y) {
    const double a = inline_hypot(x, y), b = std::hypot(x, y);
    return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
  };
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), metres(-300.0, 300.0);
  std::uniform_int_distribution<int> exponent(-1074, 1023), small_exponent(-60, 10);
  long differ = 0;
  for (int i = 0; i < 4'000'000; ++i) {
    const double x = std::ldexp(unit(rng), exponent(rng)), y = std::ldexp(unit(rng), exponent(rng));
    differ += !same(x, y);
    const double u = metres(rng), v = std::ldexp(unit(rng), small_exponent(rng));  // a near-axis walk
    differ += !same(u, v) + !same(v, u) + !same(u, metres(rng));
  }
  EXPECT_EQ(differ, 0);
  constexpr double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  constexpr double max = std::numeric_limits<double>::max(), denorm = std::numeric_limits<double>::denorm_min();
  for (const double x : {0.0, -0.0, 1.0, -3.0, 0x1p+511, 0x1p+512, 0x1p-459, 0x1p-460, max, denorm, inf, -inf, nan})
    for (const double y : {0.0, -0.0, 4.0, 0x1p-54, 0x1p+511, 0x1p-460, max, denorm, inf, -inf, nan})
      EXPECT_TRUE(same(x, y)) << x << ", " << y << ": " << inline_hypot(x, y) << " vs " << std::hypot(x, y);
}

// check_ranges (every run's check) tests each value inline (ParamInfo::allows)
// and builds the message only for a refused one: every parameter, each way a
// value can leave its range, is refused with its name and range; its
// bounds are allowed.
TEST(ParamTable, CheckRangesRefusesEveryParameterOutsideItsRangeByName) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  int refused = 0;
  for (const ParamInfo& info : param_table()) {
    std::vector<double> outside, inside;
    if (info.kind == ParamInfo::Kind::choice) {
      outside = {double(info.choices.size()), -1.0};
      inside = {0.0, double(info.choices.size() - 1)};
    } else {
      inside = {info.lo, info.hi};
      if (std::isfinite(info.lo) && info.lo > -1e15) outside.push_back(info.lo - 1.0);
      if (std::isfinite(info.hi) && info.hi < 1e15) outside.push_back(info.hi + 1.0);
      if (info.kind == ParamInfo::Kind::real) {
        outside.push_back(inf);
        outside.push_back(-inf);
        if (!info.may_be_unset) outside.push_back(nan);
        else inside.push_back(nan);
      }
    }
    for (double v : outside) {
      RunParams p;
      info.set(p, v);
      if (std::isnan(v) && !std::isnan(info.get(p))) continue;  // ic_*: an unset one reads as its default
      const std::string e = check_ranges(p);
      EXPECT_EQ(e.rfind(std::string(info.name) + " = ", 0), 0u) << info.name << " = " << v << ": " << e;
      EXPECT_NE(e.find(info.range_text()), std::string::npos) << e;
      ++refused;
    }
    for (double v : inside) {
      RunParams p;
      info.set(p, v);
      EXPECT_EQ(check_ranges(p), "") << info.name << " = " << v;
    }
  }
  EXPECT_GT(refused, int(param_table().size()));
}

TEST(SincosShift, CarryFormIsExactToRoundingUpToItsBound) { EXPECT_LT(max_shift_error<ShiftForm::carry>(), 3.5e-16); }

TEST(SincosShift, TinyFormIsExactToRoundingUpToItsBound) { EXPECT_LT(max_shift_error<ShiftForm::tiny>(), 3.5e-16); }

TEST(SincosShift, ShortFormIsExactToRoundingUpToItsBound) { EXPECT_LT(max_shift_error<ShiftForm::short_>(), 3.5e-16); }

TEST(SincosShift, StageShiftsStayWithinTheirFormsAtTheModeLimit) {
  // The bounds derived in arnold_flow.hpp, checked on random states and
  // coefficients with h * M exactly at small_shift.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi), coeff(-2.0, 2.0);
  const auto norm = [](const Vec3<double>& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); };
  double worst_tiny = 0, worst_short = 0, worst_carry = 0;
  for (int i = 0; i < 200000; ++i) {
    const double A = coeff(rng), B = coeff(rng), C = coeff(rng);
    const double M = std::max({std::fabs(A) + std::fabs(C), std::fabs(B) + std::fabs(A), std::fabs(C) + std::fabs(B)});
    double h = small_shift / M;
    while (h * M > small_shift) h = std::nextafter(h, 0.0);
    ASSERT_TRUE(small_shift_mode(h, A, B, C));
    const ArnoldCoeffs<double> kh{0.5 * h * A, 0.5 * h * B, 0.5 * h * C};
    const Vec3<double> u{angle(rng), angle(rng), angle(rng)};
    const Vec3<double> K1 = arnold_rhs(u, kh), K2 = arnold_rhs(u + K1, kh), K3 = arnold_rhs(u + K2, kh);
    const Vec3<double> K4 = arnold_rhs(u + K3 + K3, kh);
    const Vec3<double> d = K1 + K2 + K2 - K3 - K3 - K3 - K3 + K4;  // 3 x the carry shift
    worst_short = std::max({worst_short, norm(K1), norm(K3 + K3 - K2)});
    worst_tiny = std::max(worst_tiny, norm(K2 - K1));
    worst_carry = std::max(worst_carry, norm(d) / 3);
  }
  EXPECT_LE(worst_tiny, shift_bound(ShiftForm::tiny));
  EXPECT_LE(worst_short, shift_bound(ShiftForm::short_));
  EXPECT_LE(worst_carry, shift_bound(ShiftForm::carry));        // (7 L^3 + 2 L^4) / 3 at L = 0.1
  EXPECT_GT(worst_tiny, 0.25 * shift_bound(ShiftForm::tiny));   // not loose by orders (measured 0.0035)
  EXPECT_GT(worst_carry, 0.1 * shift_bound(ShiftForm::carry));  // measured 0.00026
}

TEST(SincosShift, ModeFollowsTheBoundOnEveryShift) {
  EXPECT_TRUE(small_shift_mode(0.1, 0.5, 0.25, 0.25));   // paper: 0.075
  EXPECT_TRUE(small_shift_mode(0.1, 0.65, 0.8, 0.4));    // Fig. 6 corner: 0.145
  EXPECT_FALSE(small_shift_mode(0.4, 0.5, 0.25, 0.25));  // 0.3
  EXPECT_FALSE(small_shift_mode(0.1, -2.0, 0.1, 0.1));   // |A| counts
}

TEST(Rk4Step, SmallShiftAndFullModesAgreeToRounding) {
  const ArnoldCoeffs<double> k{0.5, 0.25, 0.25};
  for (const Vec3<double> u : {Vec3<double>{0, 1, 0}, Vec3<double>{3.1, -2.9, 1.5}, Vec3<double>{-1.2, 0.4, 3.14}}) {
    const auto a = rk4_step<double>(u, k, heading_select(3), 0.1, 0.1, true);
    const auto b = rk4_step<double>(u, k, heading_select(3), 0.1, 0.1, false);
    EXPECT_NEAR(a.u.x, b.u.x, 1e-15);
    EXPECT_NEAR(a.u.y, b.u.y, 1e-15);
    EXPECT_NEAR(a.u.z, b.u.z, 1e-15);
    EXPECT_NEAR(a.dX, b.dX, 1e-16);
    EXPECT_NEAR(a.dY, b.dY, 1e-16);
  }
}

TEST(Rk4Step, CarriedTrigIsTheNewStatesToRoundingAndExactOutsideSmallShiftMode) {
  const ArnoldCoeffs<double> k{0.5, 0.25, 0.25};
  for (const Vec3<double> u : {Vec3<double>{0, 1, 0}, Vec3<double>{3.1, -2.9, 1.5}, Vec3<double>{-1.2, 0.4, 3.14}}) {
    const auto a = rk4_step<double>(u, k, heading_select(3), 0.1, 0.1, true);
    const Trig3<double> t = trig3(a.u);
    for (auto m : {&Trig3<double>::sx, &Trig3<double>::cx, &Trig3<double>::sy, &Trig3<double>::cy, &Trig3<double>::sz,
                   &Trig3<double>::cz})
      EXPECT_NEAR(a.t.*m, t.*m, 5e-16);
    const auto b = rk4_step<double>(u, k, heading_select(3), 0.5, 0.5, false);  // full sincos of the new u
    const Trig3<double> tb = trig3(b.u);
    EXPECT_TRUE(b.t.sx == tb.sx && b.t.cx == tb.cx && b.t.sy == tb.sy && b.t.cy == tb.cy && b.t.sz == tb.sz &&
                b.t.cz == tb.cz);
  }
}

namespace {
// Largest |sin(state) - carried sine| (and cosine) and |s^2 + c^2 - 1| over
// n small-shift steps from the run-start trig, against libm on the state.
std::array<double, 2> carried_trig_drift(const ArnoldCoeffs<double>& k, Vec3<double> u, long n) {
  Trig3<double> t = trig3(u);
  double angle = 0, norm = 0;
  const auto check = [&](double x, double s, double c) {
    angle = std::max({angle, std::fabs(std::sin(x) - s), std::fabs(std::cos(x) - c)});
    norm = std::max(norm, std::fabs(std::fma(s, s, c * c) - 1.0));
  };
  for (long i = 0; i < n; ++i) {
    const auto st = rk4_step(u, t, k, heading_select(3), 0.1, 0.1);
    u = st.u;
    t = st.t;
    check(u.x, t.sx, t.cx);
    check(u.y, t.sy, t.cy);
    check(u.z, t.sz, t.cz);
  }
  return {angle, norm};
}
}  // namespace

TEST(Rk4Step, CarriedTrigDriftsByRoundingOnlyOverAMillionSteps) {
  // The paper's (0.5, 0.25, 0.25) and Fig. 6's far corner, h = 0.1.
  for (const ArnoldCoeffs<double> k : {ArnoldCoeffs<double>{0.5, 0.25, 0.25}, ArnoldCoeffs<double>{0.65, 0.8, 0.4}}) {
    const auto [angle, norm] = carried_trig_drift(k, {0, 1, 0}, 1000000);
    std::cout << "drift " << k.A << "," << k.B << "," << k.C << ": trig " << angle << ", norm " << norm << "\n";
    EXPECT_LT(angle, 1e-11);
    EXPECT_LT(norm, 1e-11);
  }
}

TEST(Rk4Step, HeadingIsTheSelectedCoordinate) {
  // With A=B=C=0 the state is frozen, so one step moves the robot by
  // h_pos * (cos s, sin s) with s the DSindex coordinate.
  const ArnoldCoeffs<double> k{0, 0, 0};
  const Vec3<double> u{0.3, 1.1, -2.0};
  const double s[3] = {0.3, 1.1, -2.0};
  for (int ds = 1; ds <= 3; ++ds) {
    const auto st = rk4_step(u, k, heading_select(ds), 0.1, 0.4);
    EXPECT_NEAR(st.dX, 0.4 * std::cos(s[ds - 1]), 1e-15) << ds;
    EXPECT_NEAR(st.dY, 0.4 * std::sin(s[ds - 1]), 1e-15) << ds;
  }
}

namespace {
// Integrates the coupled system for `total` seconds with step h; returns the
// robot displacement (unbounded plane) and the unwrapped-equivalent state.
std::array<double, 5> integrate(double h, double total) {
  const ArnoldCoeffs<double> k{0.5, 0.25, 0.25};
  Vec3<double> u{0, 1, 0};
  double X = 0, Y = 0;
  const int n = int(std::lround(total / h));
  for (int i = 0; i < n; ++i) {
    const auto st = rk4_step(u, k, heading_select(3), h, h);
    u = st.u;
    X += st.dX;
    Y += st.dY;
  }
  return {std::sin(u.x), std::sin(u.y), std::sin(u.z), X, Y};
}
double distance(const std::array<double, 5>& a, const std::array<double, 5>& b) {
  double m = 0;
  for (int i = 0; i < 5; ++i) m = std::max(m, std::fabs(a[i] - b[i]));
  return m;
}
}  // namespace

TEST(Rk4Step, IsFourthOrderUnderStepHalving) {
  const double total = 20.0;
  const auto ref = integrate(0.4 / 256, total);
  const double e1 = distance(integrate(0.4, total), ref);
  const double e2 = distance(integrate(0.2, total), ref);
  const double e3 = distance(integrate(0.1, total), ref);
  EXPECT_GT(e1 / e2, 12.0);
  EXPECT_LT(e1 / e2, 20.0);
  EXPECT_GT(e2 / e3, 13.0);
  EXPECT_LT(e2 / e3, 19.0);
}

TEST(Rk4Step, ARunRelabelledWithItsHeadingInZComputesTheSameNumbers) {
  auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> angle(-3.1, 3.1), coeff(0.05, 0.9);
  for (int i = 0; i < 3000; ++i) {
    const int ds = 1 + i % 3;
    const double h = i % 2 ? 0.1 : 0.5;  // small-shift mode and full sincos
    const Vec3<double> u{angle(rng), angle(rng), angle(rng)};
    const ArnoldCoeffs<double> k{coeff(rng), coeff(rng), coeff(rng)};
    const bool small = small_shift_mode(h, k.A, k.B, k.C);
    const Rk4Step<double> want = rk4_step<double>(u, trig3(u), k, heading_select(ds), h, 0.1, small);
    const Rk4Step<double> lane =
        rk4_step<double>(to_lane(u, ds), to_lane(trig3(u), ds), to_lane(k, ds), HeadingZ{}, h, 0.1, small);
    const Vec3<double> got = from_lane(lane.u, ds);
    const Trig3<double> t = from_lane(lane.t, ds);
    ASSERT_TRUE(same(got.x, want.u.x) && same(got.y, want.u.y) && same(got.z, want.u.z)) << i;
    ASSERT_TRUE(same(t.sx, want.t.sx) && same(t.cx, want.t.cx) && same(t.sy, want.t.sy) && same(t.cy, want.t.cy) &&
                same(t.sz, want.t.sz) && same(t.cz, want.t.cz))
        << i;
    ASSERT_TRUE(same(lane.dX, want.dX) && same(lane.dY, want.dY)) << i;
    const Vec3<double> back = from_lane(to_lane(u, ds), ds);
    ASSERT_TRUE(same(back.x, u.x) && same(back.y, u.y) && same(back.z, u.z)) << i;
  }
}

// -------------------------------------------------------------- boundaries

TEST(MirrorEq7, ReflectsAboutTheLineAtOffsetFo) {
  // X = -X + 2(left + fo) and X = -X + 2(right - fo).
  EXPECT_DOUBLE_EQ(mirror_eq7(0.3, 0.0, 50.0, 0.5), 0.7);
  EXPECT_DOUBLE_EQ(mirror_eq7(-0.2, 0.0, 50.0, 0.5), 1.2);
  EXPECT_DOUBLE_EQ(mirror_eq7(49.8, 0.0, 50.0, 0.5), 49.2);
  EXPECT_DOUBLE_EQ(mirror_eq7(50.3, 0.0, 50.0, 0.5), 48.7);
  EXPECT_EQ(mirror_eq7(17.123456789, 0.0, 50.0, 0.5), 17.123456789);  // inside: bit-exact
}

TEST(MirrorEq7, KeepsAnyPositionInsideTheBand) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-500, 500);
  for (int i = 0; i < 100000; ++i) {
    const double x = mirror_eq7(u(rng), 0.0, 50.0, 0.5);
    ASSERT_GE(x, 0.5);
    ASSERT_LE(x, 49.5);
  }
}

TEST(TriangleFold, IsTheUnfoldingOfReflectingWalls) {
  EXPECT_DOUBLE_EQ(triangle_fold(11.0, 0.0, 10.0), 9.0);
  EXPECT_DOUBLE_EQ(triangle_fold(-1.0, 0.0, 10.0), 1.0);
  EXPECT_DOUBLE_EQ(triangle_fold(21.0, 0.0, 10.0), 1.0);
  EXPECT_DOUBLE_EQ(triangle_fold(-19.0, 0.0, 10.0), 1.0);
  EXPECT_DOUBLE_EQ(triangle_fold(35.0, 0.0, 10.0), 5.0);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1e4, 1e4);
  for (int i = 0; i < 100000; ++i) {
    const double w = u(rng), x = triangle_fold(w, 0.0, 10.0);
    ASSERT_GE(x, 0.0);
    ASSERT_LE(x, 10.0);
    ASSERT_NEAR(x, triangle_fold(w + 20.0, 0.0, 10.0), 1e-9);  // period 2L
  }
}

TEST(RobotMotion, NeverLeavesTheMapUnderEitherBoundary) {
  for (Boundary b : {Boundary::mirror, Boundary::fold}) {
    RunParams p = small_run(10.0);
    p.boundary = b;
    const Environment env = square_map(10.0);
    CoverageGrid grid(env, 1.0);
    RobotMotion robot(p, env, grid);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> step(-7.0, 7.0);  // steps far longer than the map
    for (int i = 0; i < 20000; ++i) {
      robot.move(step(rng), step(rng));
      const double lo = b == Boundary::mirror ? 0.5 : 0.0, hi = 10.0 - lo;
      ASSERT_GE(robot.x(), lo);
      ASSERT_LE(robot.x(), hi);
      ASSERT_GE(robot.y(), lo);
      ASSERT_LE(robot.y(), hi);
    }
  }
}

TEST(RobotMotion, PushesOutOfObstaclesByEq8) {
  RunParams p = small_run(10.0);
  const Environment env = square_map(10.0, {{4, 4, 6, 6}});
  CoverageGrid grid(env, 1.0);
  p.start_x = 3.0;
  p.start_y = 5.0;
  RobotMotion robot(p, env, grid);
  robot.move(1.2, 0.1);  // lands at (4.2, 5.1): least penetration through the left face
  EXPECT_DOUBLE_EQ(robot.x(), 3.5);
  EXPECT_DOUBLE_EQ(robot.y(), 5.1);
}

TEST(RobotMotion, ObstacleResponsesPushMirrorOrBounceAtTheFaceOfLeastPenetration) {
  RunParams p = small_run(10.0);
  const Environment env = square_map(10.0, {{4, 4, 6, 6}});
  p.start_x = 3.0;
  p.start_y = 5.0;
  auto after = [&](ObstacleResponse response) {
    p.obstacle_response = response;
    CoverageGrid grid(env, 1.0);
    RobotMotion robot(p, env, grid);
    robot.move(1.2, 0.1);  // lands at (4.2, 5.1), 0.7 m into the margin of the left face (3.5)
    const Point hit{robot.x(), robot.y()};
    robot.move(0.5, 0.0);  // then a step straight on
    return std::pair{hit, Point{robot.x(), robot.y()}};
  };
  const auto [push, push_next] = after(ObstacleResponse::push);
  EXPECT_DOUBLE_EQ(push.x, 3.5);       // onto the line at fo (Eq. 8 as printed) ...
  EXPECT_DOUBLE_EQ(push_next.x, 3.5);  // ... and pushed back there by the next step
  const auto [mirror, mirror_next] = after(ObstacleResponse::mirror);
  EXPECT_DOUBLE_EQ(mirror.x, 2.8);  // 2 * 3.5 - 4.2: reflected about that line (Eq. 7's form)
  EXPECT_DOUBLE_EQ(mirror.y, 5.1);
  EXPECT_DOUBLE_EQ(mirror_next.x, 3.3);  // the heading is unchanged: it walks back towards the face
  const auto [bounce, bounce_next] = after(ObstacleResponse::reflect);
  EXPECT_DOUBLE_EQ(bounce.x, 2.8);       // the same point ...
  EXPECT_DOUBLE_EQ(bounce_next.x, 2.3);  // ... and from then on the motion along x is reversed
  EXPECT_DOUBLE_EQ(bounce_next.y, 5.1);
}

// -------------------------------------------------------------- coverage

TEST(CoverageGrid, UsesCeilCellsWithTheLastRowClipped) {
  const CoverageGrid g(square_map(50.0), 4.0);
  EXPECT_EQ(g.nx(), 13);
  EXPECT_EQ(g.ny(), 13);
  EXPECT_EQ(g.free_cells(), 169);
  EXPECT_EQ(g.cell_x(50.0), 12);  // a point on the far wall is in the last cell
}

TEST(CoverageGrid, ACellIsBlockedWhenItsCentreIsInAnObstacle) {
  // Covers most of cell (1,1) and slivers of its neighbours: only (1,1)'s
  // centre (1.5, 1.5) is inside.
  const CoverageGrid g(square_map(4.0, {{0.9, 0.9, 2.1, 1.6}}), 1.0);
  EXPECT_EQ(g.at(1, 1), CoverageGrid::blocked);
  EXPECT_EQ(g.at(0, 0), CoverageGrid::unvisited);
  EXPECT_EQ(g.at(2, 1), CoverageGrid::unvisited);
  EXPECT_EQ(g.free_cells(), 15);
}

TEST(Supercover, MarksEveryCellOfAnAxisAlignedSegment) {
  CoverageGrid g(square_map(5.0), 1.0);
  g.mark_segment(0.5, 2.5, 4.5, 2.5);
  EXPECT_EQ(marked_cells(g), (std::set<std::pair<int, int>>{{0, 2}, {1, 2}, {2, 2}, {3, 2}, {4, 2}}));
}

TEST(Supercover, MarksBothSideCellsThroughACorner) {
  CoverageGrid g(square_map(5.0), 1.0);
  g.mark_segment(0.5, 0.5, 1.5, 1.5);
  EXPECT_EQ(marked_cells(g), (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {0, 1}, {1, 1}}));
}

TEST(Supercover, MarksTheCellsASteepSegmentCrosses) {
  CoverageGrid g(square_map(5.0), 1.0);
  g.mark_segment(1.2, 0.3, 1.9, 3.7);  // stays in column 1 through rows 0..3
  EXPECT_EQ(marked_cells(g), (std::set<std::pair<int, int>>{{1, 0}, {1, 1}, {1, 2}, {1, 3}}));
  CoverageGrid h(square_map(5.0), 1.0);
  h.mark_segment(0.2, 0.8, 2.8, 1.3);  // crosses x = 1 at y = 0.95, then y = 1 at x = 1.24
  EXPECT_EQ(marked_cells(h), (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {1, 1}, {2, 1}}));
}

TEST(Supercover, EqualsDenseSamplingOnRandomSegments) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 20.0);
  for (int trial = 0; trial < 300; ++trial) {
    const double x0 = u(rng), y0 = u(rng), x1 = u(rng), y1 = u(rng);
    CoverageGrid g(square_map(20.0), 1.5), dense(square_map(20.0), 1.5);
    g.mark_segment(x0, y0, x1, y1);
    for (int k = 0; k <= 200000; ++k) {
      const double t = k / 200000.0;
      dense.mark_point(x0 + t * (x1 - x0), y0 + t * (y1 - y0));
    }
    // Dense sampling can miss a sliver of a cell, never add one.
    const auto a = marked_cells(g), b = marked_cells(dense);
    for (const auto& c : b) ASSERT_TRUE(a.count(c)) << trial;
    ASSERT_LE(a.size(), b.size() + 2) << trial;
  }
}

TEST(Supercover, MarksEachFreeCellOnceAndSkipsBlockedCells) {
  CoverageGrid g(square_map(4.0, {{1, 0, 2, 4}}), 1.0);  // column 1 blocked
  EXPECT_EQ(g.free_cells(), 12);
  g.mark_segment(0.5, 0.5, 3.5, 0.5);
  g.mark_segment(3.5, 0.5, 0.5, 0.5);
  EXPECT_EQ(g.visited_cells(), 3);
  EXPECT_EQ(g.at(1, 0), CoverageGrid::blocked);
}

// marks_nothing (the transits' shortcut) never claims a mark would change
// nothing when it would: cells, counts, window, visits and turns, on random
// walks of points with windows and regions, over free and blocked cells;
// and it does hold for most points, as a transit's ten points to a cell.
TEST(CoverageGrid, MarksNothingOnlyWhenAMarkChangesNothing) {
  struct State {
    int visited, window_distinct;
    std::vector<CoverageGrid::Cell> cells;
    std::vector<std::uint32_t> visits;
    std::vector<std::int64_t> turns;
    std::vector<int> regions;
    bool operator==(const State&) const = default;
  };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> step(-0.3, 0.3);
  long claimed = 0, points = 0;
  for (int trial = 0; trial < 40; ++trial) {
    CoverageGrid g(square_map(6.0, {{2.2, 2.2, 3.8, 3.8}}), 1.0);
    auto regions = std::make_shared<std::vector<int>>(std::size_t(g.nx() * g.ny()));
    for (std::size_t k = 0; k < regions->size(); ++k) (*regions)[k] = int(k % 3);
    g.count_regions(regions, 3);
    const auto state = [&g] {
      State st{g.visited_cells(), g.window_distinct(), {}, g.visits(), {g.turns(), g.turns() + 4}, {}};
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) st.cells.push_back(g.at(i, j));
      for (int z = 0; z < 3; ++z) st.regions.push_back(g.region_visited(z));
      return st;
    };
    double x = 0.5, y = 0.5;
    for (int n = 0; n < 2000; ++n) {
      if (n % 150 == 0 && trial % 2 == 0) g.begin_window();  // a new segment's window (map zoning)
      x = std::clamp(x + step(rng), 0.0, 6.0);
      y = std::clamp(y + step(rng), 0.0, 6.0);
      const int i = g.cell_x(x), j = g.cell_y(y);
      const bool nothing = g.marks_nothing(i, j);
      const State before = state();
      g.mark_cell(i, j);
      if (nothing) {
        ASSERT_EQ(state(), before) << "trial " << trial << ", point " << n;
      }
      claimed += nothing;
      ++points;
    }
  }
  EXPECT_GT(claimed, points / 2);
}

// ---------------------------------------------------- metrics and outcomes

TEST(Metrics, TOptIsTheLawnmowerTime) {
  EXPECT_DOUBLE_EQ(t_opt(0.9, 2500, 1.0, 1.0), 2250.0);  // Table 1 row 1 reference
  EXPECT_DOUBLE_EQ(6950.0 / t_opt(0.9, 2500, 1.0, 1.0), 6950.0 / 2250.0);
  EXPECT_DOUBLE_EQ(t_opt(0.9, 2500, 4.0, 1.0), 562.5);
}

TEST(Metrics, CellsNeededIsTheSmallestCountReachingDc) {
  EXPECT_EQ(cells_needed(0.9, 2500), 2250);
  EXPECT_EQ(cells_needed(0.9, 169), 153);  // 152.1 -> 153
  EXPECT_EQ(cells_needed(1.0, 7), 7);
  EXPECT_EQ(cells_needed(0.5, 16), 8);
}

TEST(Metrics, CoverageOfAllCellsCountsTheObstacleCellsAsCovered) {
  // 10 x 10 cells, a 4 x 4 obstacle: 84 free, 16 blocked.
  const Environment env = square_map(10.0, {{3, 3, 7, 7}});
  const CoverageGrid g(env, 1.0);
  ASSERT_EQ(g.free_cells(), 84);
  ASSERT_EQ(g.blocked_cells(), 16);
  RunParams p = small_run(10.0);
  p.dc = 0.9;
  EXPECT_EQ(cells_needed(p, g), 76);  // 75.6 of 84
  EXPECT_EQ(cells_total(p, g), 84);
  EXPECT_DOUBLE_EQ(coverage_rate(p, g, 42), 0.5);
  p.coverage_cells = CoverageCells::all_cells;
  EXPECT_EQ(cells_needed(p, g), 90 - 16);  // 90 of 100 cells, 16 of them the obstacle's
  EXPECT_EQ(cells_total(p, g), 100);
  EXPECT_DOUBLE_EQ(coverage_rate(p, g, 42), 0.58);
  p.dc = 0.1;
  EXPECT_EQ(cells_needed(p, g), 0);  // the obstacle alone is 16%
  // A run: it stops at 74 visited free cells, reporting tc over all cells.
  p.dc = 0.9;
  p.start_x = p.start_y = 1.0;
  const RunResult r = run_planner(p, env);
  ASSERT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.visited_cells, 74);
  EXPECT_DOUBLE_EQ(r.final_coverage, 0.9);
}

TEST(Planner, ReportsCoverageTOptAndPrOnATinyMap) {
  RunParams p = small_run(4.0);
  p.dc = 0.5;
  p.fo = 0.25;
  const RunResult r = run_planner(p, square_map(4.0));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_EQ(r.free_cells, 16);
  EXPECT_GE(r.visited_cells, 8);
  EXPECT_DOUBLE_EQ(r.final_coverage, r.visited_cells / 16.0);
  EXPECT_DOUBLE_EQ(r.t_opt, 0.5 * 16 / 1.0);
  EXPECT_DOUBLE_EQ(r.pr, r.coverage_time / r.t_opt);
  EXPECT_NEAR(r.coverage_time, r.steps * p.dt, 1e-9);
  EXPECT_DOUBLE_EQ(r.t_end, r.coverage_time);
}

TEST(Planner, OriginalArnoldOnTable1Row1EndsOkInThousandsOfSeconds) {
  RunParams p = small_run(50.0);
  p.ds_index = 3;
  const RunResult r = run_planner(p, square_map(50.0));
  ASSERT_EQ(r.status, Status::ok);
  EXPECT_GT(r.coverage_time, 1000.0);
  EXPECT_LT(r.coverage_time, 45000.0);
  EXPECT_EQ(r.visited_cells, 2250);
}

TEST(Planner, IsAPureFunctionOfItsParameters) {
  RunParams p = small_run(20.0);
  const RunResult a = run_planner(p, square_map(20.0)), b = run_planner(p, square_map(20.0));
  EXPECT_EQ(a.coverage_time, b.coverage_time);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.final_x, b.final_x);
  EXPECT_EQ(a.final_y, b.final_y);
}

TEST(Planner, StartInsideAnObstacleIsInvalid) {
  RunParams p = small_run(10.0);
  p.start_x = p.start_y = 5.0;
  const RunResult r = run_planner(p, square_map(10.0, {{4, 4, 6, 6}}));
  EXPECT_EQ(r.status, Status::invalid);
  EXPECT_NE(r.message.find("inside obstacle #0"), std::string::npos) << r.message;
}

TEST(Planner, OutOfRangeParameterIsInvalidAndNamed) {
  RunParams p = small_run(10.0);
  p.ds_index = 4;
  const RunResult r = run_planner(p, square_map(10.0));
  EXPECT_EQ(r.status, Status::invalid);
  EXPECT_NE(r.message.find("ds_index"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("[1, 3]"), std::string::npos) << r.message;
}

TEST(Planner, TimeBudgetEndsTheRunAsTimeout) {
  RunParams p = small_run(50.0);
  p.max_time = 30.0;
  const RunResult r = run_planner(p, square_map(50.0));
  EXPECT_EQ(r.status, Status::timeout);
  EXPECT_TRUE(std::isnan(r.coverage_time));
  EXPECT_TRUE(std::isnan(r.pr));
  EXPECT_GE(r.t_end, 30.0);
  EXPECT_LT(r.t_end, 30.0 + 2 * p.dt);
}

TEST(Planner, NoNewCellForStuckTimeEndsTheRunAsStuck) {
  RunParams p = small_run(10.0);
  p.A = p.B = p.C = 0.0;  // frozen heading: the robot slides along one wall
  p.stuck_time = 50.0;
  const RunResult r = run_planner(p, square_map(10.0));
  EXPECT_EQ(r.status, Status::stuck);
  EXPECT_LT(r.t_end, 100.0);
}

TEST(Planner, StepSizeCollapseEndsTheRunAsDiverged) {
  RunParams p = small_run(10.0);
  p.integrator = Integrator::rk4_doubling;
  p.A = p.B = p.C = 900.0;  // stiff: step doubling never meets ep
  p.ep = 1e-15;
  p.dt_min = 0.01;  // 0.1 -> 0.05 -> 0.025 -> 0.0125 -> 0.00625 < dt_min
  const RunResult r = run_planner(p, square_map(10.0));
  EXPECT_EQ(r.status, Status::diverged);
  EXPECT_EQ(r.dt_halvings, 4);
  EXPECT_NE(r.message.find("dt_min"), std::string::npos) << r.message;
}

TEST(Planner, StepDoublingEqualsFixedStepForThePapersParameters) {
  // docs/spec.md §2: for the paper's parameters doubling never halves dt, so both
  // integrators give the same run, bit for bit.
  for (int ds = 1; ds <= 3; ++ds) {
    RunParams p = small_run(50.0);
    p.sr = 4.0;
    p.ds_index = ds;
    const RunResult fixed = run_planner(p, square_map(50.0));
    p.integrator = Integrator::rk4_doubling;
    const RunResult doubling = run_planner(p, square_map(50.0));
    EXPECT_EQ(doubling.dt_halvings, 0);
    EXPECT_EQ(doubling.status, fixed.status);
    EXPECT_EQ(doubling.coverage_time, fixed.coverage_time);
    EXPECT_EQ(doubling.steps, fixed.steps);
  }
}

TEST(Planner, StepDoublingHalvesWhenTheToleranceIsTight) {
  RunParams p = small_run(20.0);
  p.integrator = Integrator::rk4_doubling;
  p.ep = 1e-12;
  p.dc = 0.3;
  const RunResult r = run_planner(p, square_map(20.0));
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_GT(r.dt_halvings, 0);
}

TEST(Planner, ScalingFactorStretchesThePathAtConstantSpeed) {
  // f scales positions: the heading sequence per step is unchanged, so with a
  // frozen heading the robot covers f times the distance per step.
  RunParams p = small_run(50.0);
  p.A = p.B = p.C = 0.0;
  p.ic_z = 0.0;       // heading +X
  p.max_time = 5.95;  // the 20th step ends at t = 6.0
  p.start_x = 1.0;
  p.start_y = 25.0;
  p.f = 3.0;
  const RunResult r = run_planner(p, square_map(50.0));
  EXPECT_EQ(r.steps, 20);             // 6 s of robot time in steps of f*dt = 0.3 s
  EXPECT_NEAR(r.final_x, 7.0, 1e-9);  // moved v * t = 6 m
}

TEST(Planner, PointSamplingNeverCoversMoreThanSegments) {
  RunParams p = small_run(50.0);
  p.f = 6.0;
  p.max_time = 2000.0;
  p.dc = 1.0;
  const RunResult seg = run_planner(p, square_map(50.0));
  p.sampling = Sampling::points;
  const RunResult pts = run_planner(p, square_map(50.0));
  EXPECT_LT(pts.visited_cells, seg.visited_cells);
}

TEST(FormatNumber, IsTheShortestTextThatReadsBackAsTheSameDouble) {
  EXPECT_EQ(format_number(0.3), "0.3");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.30000000000000004");  // iostream's default showed "0.3"
  EXPECT_EQ(format_number(0.2 + 3 * 0.05), "0.35000000000000003");
  EXPECT_EQ(format_number(1185.0999999999999), "1185.1");
  EXPECT_EQ(format_number(10000), "10000");
  EXPECT_EQ(format_number(1e6), "1e+06");
  EXPECT_EQ(format_number(9.007199254740992e15), "9007199254740992");
  EXPECT_EQ(format_number(-0.5), "-0.5");
  EXPECT_EQ(format_number(std::nan("")), "nan");
  EXPECT_EQ(format_number(-INFINITY), "-inf");
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int i = 0; i < 10000; ++i) {
    const double v = i % 2 ? u(rng) : std::ldexp(u(rng), int(rng() % 200) - 100);
    EXPECT_EQ(std::strtod(format_number(v).c_str(), nullptr), v) << format_number(v);
  }
}

// The environment loader's messages show positions to 6 digits, as they did
// when they printed through iostream (tests/engine/test_engine_bad_input.cpp).
TEST(FormatNumber, WithSignificantDigitsIsWhatIostreamPrints) {
  EXPECT_EQ(format_number(0.8 * 12, 6), "9.6");
  EXPECT_EQ(format_number((0.8 + 0.4) * 12, 6), "14.4");
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  std::vector<double> values{0.0, -0.0, 1e6, 1e-5, 123456.5, 5e17, INFINITY, -INFINITY, std::nan(""), -std::nan("")};
  for (int i = 0; i < 10000; ++i) values.push_back(i % 2 ? u(rng) : std::ldexp(u(rng), int(rng() % 200) - 100));
  for (double v : values) {
    std::ostringstream os;
    os << v;
    EXPECT_EQ(format_number(v, 6), os.str()) << v;
  }
}

// The inline cases of mark_segment (a step that stays in its cell or enters a
// side neighbour) against dense sampling, on the steps the planners take:
// shorter than a cell, from random points, many ending near an edge.
TEST(Supercover, EqualsDenseSamplingOnStepsShorterThanACell) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 20.0), step(-1.4, 1.4);
  int side_steps = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double x0 = u(rng), y0 = u(rng);
    const double x1 = std::clamp(x0 + step(rng), 0.0, 20.0), y1 = std::clamp(y0 + step(rng), 0.0, 20.0);
    CoverageGrid g(square_map(20.0), 1.5), dense(square_map(20.0), 1.5);
    g.mark_segment(x0, y0, x1, y1);
    for (int k = 0; k <= 20000; ++k) {
      const double t = k / 20000.0;
      dense.mark_point(x0 + t * (x1 - x0), y0 + t * (y1 - y0));
    }
    const auto a = marked_cells(g), b = marked_cells(dense);
    const int di = std::abs(g.cell_x(x1) - g.cell_x(x0)), dj = std::abs(g.cell_y(y1) - g.cell_y(y0));
    if (di + dj <= 1) {
      side_steps += di + dj;
      ASSERT_EQ(a, b) << trial;  // no corner to pass: exactly the cells sampled
    } else {
      for (const auto& c : b) ASSERT_TRUE(a.count(c)) << trial;
      ASSERT_LE(a.size(), b.size() + 2) << trial;
    }
  }
  EXPECT_GT(side_steps, 500);  // the side-neighbour case was exercised
}

// mark_step (both ends' cells known) leaves the grid as mark_segment does:
// cells, visited count, visits, turns, and a window's distinct cells. Random
// walks of moves up to two cells long on a map with a blocked square, some
// with a window begun mid-walk (the start cell not yet stamped in it), some
// starting after another cell was marked (the start cell not the one
// marked last), so each case that must not be skipped is exercised.
TEST(Supercover, MarkStepLeavesTheGridAsMarkSegmentDoes) {
  Environment env = square_map(20.0);
  env.obstacles.push_back({8, 8, 12, 12});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 20.0), step(-2.5, 2.5);
  for (int walk = 0; walk < 200; ++walk) {
    CoverageGrid a(env, 1.0), b(env, 1.0);
    double x = u(rng), y = u(rng);
    a.mark_point(x, y);
    b.mark_point(x, y);
    if (walk % 3 == 1) {  // another cell marked last, in both
      const double ox = u(rng), oy = u(rng);
      a.mark_point(ox, oy);
      b.mark_point(ox, oy);
    }
    for (int m = 0; m < 400; ++m) {
      if (walk % 2 == 0 && m == 200) a.begin_window(), b.begin_window();
      const double nx = std::clamp(x + step(rng), 0.0, 20.0), ny = std::clamp(y + step(rng), 0.0, 20.0);
      const int i = a.cell_x(x), j = a.cell_y(y), i1 = a.cell_x(nx), j1 = a.cell_y(ny);
      a.mark_segment(x, y, nx, ny);
      if (i1 != i || j1 != j) b.mark_step(i, j, i1, j1, x, y, nx, ny);
      x = nx, y = ny;
    }
    ASSERT_EQ(marked_cells(a), marked_cells(b)) << walk;
    ASSERT_EQ(a.visited_cells(), b.visited_cells()) << walk;
    ASSERT_EQ(a.visits(), b.visits()) << walk;
    for (int k = 0; k < 4; ++k) ASSERT_EQ(a.turns()[k], b.turns()[k]) << walk;
    ASSERT_EQ(a.window_distinct(), b.window_distinct()) << walk;
  }
}
