// Kernels: the chaotic flows of kernels/systems/flows/ (docs/spec.md §2,
// "Other chaotic flows"): each right-hand side is its published equations,
// the shared RK4 step is classic RK4 with the robot coupled as to the Arnold
// flow, each flow stays on its attractor with its default coefficients, and
// drives the Arnold planner family to coverage. That every lane width gives
// the scalar path's numbers is SweepRunner.RowsAreBitIdenticalAcrossWidths-
// ThreadsAndBatches (test_engine).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "kernels/planners/planner.hpp"
#include "kernels/systems/flow.hpp"
#include "kernels/systems/system_list.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;
using chaosweep::test::small_run;
using chaosweep::test::square_map;

namespace {

template <class F>
FlowCoeffs<double> defaults_of() {
  return {F::defaults.a, F::defaults.b, F::defaults.c, F::defaults.d};
}

int system_index(std::string_view name) {
  for (int s = 0; s < system_count; ++s)
    if (system_name(s) == name) return s;
  return -1;
}

// The plain RK4 of a 3-D right-hand side, with the heading coordinate's
// cos/sin averaged like the positions (libm's cos/sin, no wrapping).
template <class F>
FlowStep<double> plain_rk4(const Vec3<double>& u, const FlowCoeffs<double>& k, int ds, double h, double h_pos) {
  auto add = [](const Vec3<double>& a, const Vec3<double>& b, double s) {
    return Vec3<double>{a.x + s * b.x, a.y + s * b.y, a.z + s * b.z};
  };
  auto heading = [&](const Vec3<double>& v) { return ds == 1 ? v.x : ds == 2 ? v.y : v.z; };
  const Vec3<double> k1 = F::rhs(u, k), u2 = add(u, k1, h / 2), k2 = F::rhs(u2, k), u3 = add(u, k2, h / 2),
                     k3 = F::rhs(u3, k), u4 = add(u, k3, h), k4 = F::rhs(u4, k);
  FlowStep<double> s;
  s.u = {u.x + h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x), u.y + h / 6 * (k1.y + 2 * k2.y + 2 * k3.y + k4.y),
         u.z + h / 6 * (k1.z + 2 * k2.z + 2 * k3.z + k4.z)};
  const double a[] = {heading(u), heading(u2), heading(u3), heading(u4)};
  s.dX = h_pos / 6 * (std::cos(a[0]) + 2 * std::cos(a[1]) + 2 * std::cos(a[2]) + std::cos(a[3]));
  s.dY = h_pos / 6 * (std::sin(a[0]) + 2 * std::sin(a[1]) + 2 * std::sin(a[2]) + std::sin(a[3]));
  return s;
}

}  // namespace

TEST(Flows, RightHandSidesAreTheirPublishedEquations) {
  const Vec3<double> u{1.5, -2.0, 3.25};
  const double x = u.x, y = u.y, z = u.z;
  {
    const Vec3<double> d = Lorenz::rhs(u, defaults_of<Lorenz>());
    EXPECT_NEAR(d.x, 10.0 * (y - x), 1e-13);
    EXPECT_NEAR(d.y, x * (28.0 - z) - y, 1e-13);
    EXPECT_NEAR(d.z, x * y - 8.0 / 3.0 * z, 1e-13);
  }
  {
    const Vec3<double> d = Chen::rhs(u, defaults_of<Chen>());
    EXPECT_NEAR(d.x, 35.0 * (y - x), 1e-13);
    EXPECT_NEAR(d.y, (28.0 - 35.0) * x - x * z + 28.0 * y, 1e-13);
    EXPECT_NEAR(d.z, x * y - 3.0 * z, 1e-13);
  }
  for (double xc : {-2.5, -0.5, 0.0, 0.75, 3.0}) {  // every piece of Chua's diode
    const Vec3<double> v{xc, y, z};
    const double m0 = -8.0 / 7.0, m1 = -5.0 / 7.0;
    const double g = std::fabs(xc) <= 1 ? m0 * xc : m1 * xc + (m0 - m1) * (xc > 0 ? 1 : -1);
    const Vec3<double> d = Chua::rhs(v, defaults_of<Chua>());
    EXPECT_NEAR(d.x, 15.6 * (y - xc - g), 1e-12) << "x = " << xc;
    EXPECT_NEAR(d.y, xc - y + z, 1e-13);
    EXPECT_NEAR(d.z, -28.0 * y, 1e-13);
  }
}

TEST(Flows, TheSharedStepIsClassicRk4WithTheRobotCoupledByItsHeadingCoordinate) {
  for (int ds = 1; ds <= 3; ++ds) {
    const Vec3<double> u{0.3, -1.2, 2.0};  // headings within [-pi, pi]: no wrap
    const HeadingSelect<double> hs = heading_select(ds);
    const FlowStep<double> a = flow_rk4_step<Chua>(u, defaults_of<Chua>(), hs, 0.01, 0.02);
    const FlowStep<double> b = plain_rk4<Chua>(u, defaults_of<Chua>(), ds, 0.01, 0.02);
    EXPECT_NEAR(a.u.x, b.u.x, 1e-14);
    EXPECT_NEAR(a.u.y, b.u.y, 1e-14);
    EXPECT_NEAR(a.u.z, b.u.z, 1e-14);
    EXPECT_NEAR(a.dX, b.dX, 1e-15) << "ds = " << ds;
    EXPECT_NEAR(a.dY, b.dY, 1e-15) << "ds = " << ds;
  }
  // A heading coordinate far outside [-pi, pi] (a Lorenz z) is the same angle.
  const Vec3<double> u{1.0, 2.0, 27.0};
  const FlowStep<double> a = flow_rk4_step<Lorenz>(u, defaults_of<Lorenz>(), heading_select(3), 0.001, 0.001);
  const FlowStep<double> b = plain_rk4<Lorenz>(u, defaults_of<Lorenz>(), 3, 0.001, 0.001);
  EXPECT_NEAR(a.dX, b.dX, 1e-15);
  EXPECT_NEAR(a.dY, b.dY, 1e-15);
}

// From its default initial state at dt = 0.01, each flow settles on its
// strange attractor: bounded, away from its fixed points, and visiting both
// of its lobes (x changes sign again and again).
TEST(Flows, EachStaysOnItsAttractorWithItsDefaultCoefficients) {
  struct Want {
    const char* name;
    double bound;  // |x|, |y|, |z| stay below it
  };
  for (const Want w : {Want{"lorenz", 60.0}, Want{"chen", 60.0}, Want{"chua", 4.0}}) {
    const int s = system_index(w.name);
    ASSERT_GE(s, 1) << w.name;
    with_flow(s, [&](auto tag) {
      using F = typename decltype(tag)::type;
      Vec3<double> u{F::defaults.ic[0], F::defaults.ic[1], F::defaults.ic[2]};
      int sign_changes = 0;
      double min_speed = 1e300;
      for (int i = 0; i < 40000; ++i) {
        const double x0 = u.x;
        u = flow_rk4_step<F>(u, defaults_of<F>(), heading_select(3), 0.01, 0.01).u;
        ASSERT_LT(std::fabs(u.x) + std::fabs(u.y) + std::fabs(u.z), 3 * w.bound) << w.name << " step " << i;
        if (i > 5000) {
          sign_changes += (x0 < 0) != (u.x < 0);
          const Vec3<double> d = F::rhs(u, defaults_of<F>());
          min_speed = std::min(min_speed, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
        }
      }
      EXPECT_GT(sign_changes, 20) << w.name << ": stays on one lobe";
      EXPECT_GT(min_speed, 1e-3) << w.name << ": settles at a fixed point";
    });
  }
}

TEST(Flows, EachDrivesTheArnoldPlannerToCoverageWithItsNameInTheParameters) {
  for (const char* name : {"lorenz", "chen", "chua"}) {
    RunParams p = small_run(10.0);
    p.system = system_index(name);
    p.dt = 0.001;  // as experiments/flows.toml: the robot's step f v dt = 0.1 m
    p.f = 100;
    p.dc = 0.8;
    p.max_time = 20000;
    const RunResult r = run_planner(p, square_map(10.0, {{4, 4, 6, 6}}));
    // Chua's double scroll, its z as the heading, covers slowly (its z spans
    // a little over a turn): it moves the robot around the map, short of dc.
    if (std::string_view(name) == "chua") {
      EXPECT_EQ(r.status, Status::timeout) << r.message;
      EXPECT_GE(r.final_coverage, 0.3);
      continue;
    }
    EXPECT_EQ(r.status, Status::ok) << name << ": " << r.message;
    EXPECT_GE(r.final_coverage, 0.8) << name;
  }
}

TEST(Flows, CoefficientsAFlowDoesNotHaveAndOtherPlannersAreRefusedByName) {
  const Environment env = square_map(10.0);
  RunParams p = small_run(10.0);
  p.system = system_index("lorenz");
  p.sys_d = 1.0;  // Lorenz has three
  std::string e = validate_run(p, env);
  EXPECT_TRUE(chaosweep::test::has(e, "sys_d")) << e;
  EXPECT_TRUE(chaosweep::test::has(e, "sigma, rho, beta")) << e;
  p.sys_d = unset;
  p.planner = Planner::chebyshev;
  e = validate_run(p, env);
  EXPECT_TRUE(chaosweep::test::has(e, "system = lorenz drives only planner = arnold")) << e;
  RunParams q = small_run(10.0);
  q.sys_a = 2.0;  // the Arnold flow takes A, B, C
  e = validate_run(q, env);
  EXPECT_TRUE(chaosweep::test::has(e, "sys_a is set but system = arnold")) << e;
  // The defaults fill what is unset; a set coefficient is used as given.
  p = small_run(10.0);
  p.system = system_index("chen");
  p.sys_b = 2.5;
  const FlowCoeffs<double> k = flow_coeffs(p);
  EXPECT_EQ((std::vector<double>{k.a, k.b, k.c}), (std::vector<double>{35.0, 2.5, 28.0}));
  // So does the initial state, per coordinate: Chua's default is (0.7, 0, 0),
  // and an Arnold run's (0, 1, 0) as before ic could be unset.
  p.system = system_index("chua");
  p.ic_y = 0.25;
  const Vec3<double> u = system_ic(p);
  EXPECT_EQ((std::vector<double>{u.x, u.y, u.z}), (std::vector<double>{0.7, 0.25, 0.0}));
  // A flow's runs are a variant of their own.
  EXPECT_EQ(variant_name(p), "chua");
  p.f = 100;
  p.index_switching = 1;
  EXPECT_EQ(variant_name(p), "chua+index_switching+scaling");
  const Vec3<double> a = system_ic(RunParams{});
  EXPECT_EQ((std::vector<double>{a.x, a.y, a.z}), (std::vector<double>{0.0, 1.0, 0.0}));
}
