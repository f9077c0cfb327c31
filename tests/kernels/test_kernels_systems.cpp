// Kernels: the chaotic flows and maps of kernels/systems/ (docs/spec.md §2,
// "Other chaotic flows", "Chaotic maps"): each right-hand side or iteration
// is its published equations, the shared RK4 step is classic RK4 with the
// robot coupled as to the Arnold flow, a map's step is one iteration, each
// system stays on its attractor with its default coefficients, and drives
// the Arnold planner family to coverage. That every lane width gives
// the scalar path's numbers is SweepRunner.RowsAreBitIdenticalAcrossWidths-
// ThreadsAndBatches (test_engine).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "kernels/planners/planner.hpp"
#include "kernels/systems/system_list.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;
using chaosweep::test::small_run;
using chaosweep::test::square_map;

namespace {

template <class F>
SystemCoeffs<double> defaults_of() {
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
SystemStep<double> plain_rk4(const Vec3<double>& u, const SystemCoeffs<double>& k, int ds, double h, double h_pos) {
  auto add = [](const Vec3<double>& a, const Vec3<double>& b, double s) {
    return Vec3<double>{a.x + s * b.x, a.y + s * b.y, a.z + s * b.z};
  };
  auto heading = [&](const Vec3<double>& v) { return ds == 1 ? v.x : ds == 2 ? v.y : v.z; };
  const Vec3<double> k1 = F::rhs(u, k), u2 = add(u, k1, h / 2), k2 = F::rhs(u2, k), u3 = add(u, k2, h / 2),
                     k3 = F::rhs(u3, k), u4 = add(u, k3, h), k4 = F::rhs(u4, k);
  SystemStep<double> s;
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
    const SystemStep<double> a = flow_rk4_step<Chua>(u, defaults_of<Chua>(), hs, 0.01, 0.02);
    const SystemStep<double> b = plain_rk4<Chua>(u, defaults_of<Chua>(), ds, 0.01, 0.02);
    EXPECT_NEAR(a.u.x, b.u.x, 1e-14);
    EXPECT_NEAR(a.u.y, b.u.y, 1e-14);
    EXPECT_NEAR(a.u.z, b.u.z, 1e-14);
    EXPECT_NEAR(a.dX, b.dX, 1e-15) << "ds = " << ds;
    EXPECT_NEAR(a.dY, b.dY, 1e-15) << "ds = " << ds;
  }
  // A heading coordinate far outside [-pi, pi] (a Lorenz z) is the same angle.
  const Vec3<double> u{1.0, 2.0, 27.0};
  const SystemStep<double> a = flow_rk4_step<Lorenz>(u, defaults_of<Lorenz>(), heading_select(3), 0.001, 0.001);
  const SystemStep<double> b = plain_rk4<Lorenz>(u, defaults_of<Lorenz>(), 3, 0.001, 0.001);
  EXPECT_NEAR(a.dX, b.dX, 1e-15);
  EXPECT_NEAR(a.dY, b.dY, 1e-15);
}

// The Arnold flow is listed system 0, a carried system: its own step (carried
// trig, small-shift stages, both modes) is the same RK4 step as the shared
// flow step of its right-hand side, to rounding (the state mod 2 pi), and a
// run starts from its initial state wrapped; its coefficients are A, B, C.
TEST(Flows, TheArnoldFlowIsListedAndItsOwnStepIsTheSharedRk4OfItsField) {
  EXPECT_EQ(system_index("arnold"), arnold_system);
  static_assert(CarriedSystem<Arnold> && !CarriedSystem<Lorenz> && !CarriedSystem<Chirikov>);
  const SystemCoeffs<double> k{1.0, 0.7, 0.43, 0.0};
  for (double h : {0.1, 0.5}) {  // 0.1: small-shift mode; 0.5: full sincos
    EXPECT_EQ(Arnold::small(k, h), h == 0.1);
    for (int ds = 1; ds <= 3; ++ds) {
      const Vec3<double> u{0.3, -1.2, 2.9};
      const HeadingSelect<double> hs = heading_select(ds);
      const Rk4Step<double> own = step_with_carry<Arnold>(u, Arnold::carry(u), k, hs, h, 0.2);
      const SystemStep<double> shared = flow_rk4_step<Arnold>(u, k, hs, h, 0.2);
      EXPECT_NEAR(wrap_pi(own.u.x - shared.u.x), 0.0, 1e-14) << "h " << h << " ds " << ds;
      EXPECT_NEAR(wrap_pi(own.u.y - shared.u.y), 0.0, 1e-14) << "h " << h << " ds " << ds;
      EXPECT_NEAR(wrap_pi(own.u.z - shared.u.z), 0.0, 1e-14) << "h " << h << " ds " << ds;
      EXPECT_NEAR(own.dX, shared.dX, 1e-15) << "h " << h << " ds " << ds;
      EXPECT_NEAR(own.dY, shared.dY, 1e-15) << "h " << h << " ds " << ds;
      // The carry it hands on is the trig of the state it reached.
      const Trig3<double> t = Arnold::carry(own.u);
      EXPECT_NEAR(own.t.sx, t.sx, 1e-14);
      EXPECT_NEAR(own.t.cz, t.cz, 1e-14);
    }
  }
  RunParams p;
  p.A = 1.0, p.B = 0.7, p.C = 0.43, p.sys_a = 5.0;  // sys_* are not Arnold's
  const SystemCoeffs<double> got = system_coeffs(p);
  EXPECT_EQ(got.a, 1.0);
  EXPECT_EQ(got.b, 0.7);
  EXPECT_EQ(got.c, 0.43);
  const Vec3<double> start = system_start(arnold_system, {4.0, -4.0, 1.0});
  EXPECT_NEAR(start.x, 4.0 - 2 * M_PI, 1e-15);
  EXPECT_NEAR(start.y, 2 * M_PI - 4.0, 1e-15);
  EXPECT_EQ(start.z, 1.0);
  EXPECT_EQ(system_start(system_index("lorenz"), {4.0, -4.0, 1.0}).x, 4.0);  // not angles
}

// How far a system moves u: a flow's speed, a map's jump to its image (both
// 0 at a fixed point).
template <class F>
double motion(const Vec3<double>& u) {
  Vec3<double> d;
  if constexpr (ChaoticMap<F>) {
    const Vec3<double> v = F::iterate(u, defaults_of<F>());
    d = {v.x - u.x, v.y - u.y, v.z - u.z};
  } else {
    d = F::rhs(u, defaults_of<F>());
  }
  return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

// From its default initial state (a flow at dt = 0.01), each system settles
// on its strange attractor: bounded, away from its fixed points, and
// visiting both of its lobes (x changes sign again and again).
TEST(Flows, EachSystemStaysOnItsAttractorWithItsDefaultCoefficients) {
  struct Want {
    const char* name;
    double bound;  // |x|, |y|, |z| stay below it
  };
  for (const Want w : {Want{"lorenz", 60.0}, Want{"chen", 60.0}, Want{"chua", 4.0}, Want{"chirikov", 3.2}}) {
    const int s = system_index(w.name);
    ASSERT_GE(s, 1) << w.name;
    with_system(s, [&](auto tag) {
      using F = typename decltype(tag)::type;
      Vec3<double> u{F::defaults.ic[0], F::defaults.ic[1], F::defaults.ic[2]};
      int sign_changes = 0;
      double min_motion = 1e300;
      for (int i = 0; i < 40000; ++i) {
        const double x0 = u.x;
        u = system_step<F>(u, defaults_of<F>(), heading_select(1), 0.01, 0.01).u;
        ASSERT_LT(std::fabs(u.x) + std::fabs(u.y) + std::fabs(u.z), 3 * w.bound) << w.name << " step " << i;
        if (i > 5000) {
          sign_changes += (x0 < 0) != (u.x < 0);
          min_motion = std::min(min_motion, motion<F>(u));
        }
      }
      EXPECT_GT(sign_changes, 20) << w.name << ": stays on one lobe";
      EXPECT_GT(min_motion, 1e-3) << w.name << ": settles at a fixed point";
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
  const SystemCoeffs<double> k = system_coeffs(p);
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

// The maps of kernels/systems/maps/ (docs/spec.md §2, "Chaotic maps"): one
// iteration per step, the robot moving f v dt along the heading of the state
// it leaves.
TEST(Maps, ChirikovIsTheStandardMapAndTheRobotMovesAlongTheStateItLeaves) {
  const SystemCoeffs<double> k = defaults_of<Chirikov>();
  ASSERT_EQ(k.a, 6.0);
  for (const Vec3<double> u :
       {Vec3<double>{0.5, 0.25, 0.0}, Vec3<double>{-3.0, 2.9, 0.0}, Vec3<double>{3.1, -1.0, 0.0}}) {
    const Vec3<double> v = Chirikov::iterate(u, k);
    const double y = std::remainder(u.y + 6.0 * std::sin(u.x), 2 * M_PI);  // mod 2 pi into [-pi, pi]
    const double x = std::remainder(u.x + y, 2 * M_PI);
    EXPECT_NEAR(v.y, y, 1e-13);
    EXPECT_NEAR(v.x, x, 1e-13);
    EXPECT_EQ(v.z, 0.0);
    for (int ds : {1, 2}) {
      const SystemStep<double> s = system_step<Chirikov>(u, k, heading_select(ds), 0.1, 0.7);
      const double heading = ds == 1 ? u.x : u.y;
      EXPECT_NEAR(s.dX, 0.7 * std::cos(heading), 1e-15);
      EXPECT_NEAR(s.dY, 0.7 * std::sin(heading), 1e-15);
      EXPECT_EQ(s.u.x, v.x);  // the step is one iteration, whatever dt
    }
  }
  // Its headings cover the circle with no drift: the mean heading vector of
  // a long orbit is near 0.
  Vec3<double> u{0.5, 0.25, 0.0};
  double cx = 0, cy = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const SystemStep<double> s = system_step<Chirikov>(u, k, heading_select(1), 1.0, 1.0);
    cx += s.dX;
    cy += s.dY;
    u = s.u;
  }
  EXPECT_LT(std::hypot(cx, cy) / n, 0.01);
}

TEST(Maps, ChirikovDrivesTheArnoldPlannerToCoverageWithAndWithoutIndexSwitching) {
  for (int is : {0, 1}) {
    RunParams p = small_run(10.0);
    p.system = system_index("chirikov");
    p.ds_index = 1;
    p.dt = 1;
    p.index_switching = is;
    p.dc = 0.8;
    p.max_time = 20000;
    const RunResult r = run_planner(p, square_map(10.0, {{4, 4, 6, 6}}));
    EXPECT_EQ(r.status, Status::ok) << r.message;
    EXPECT_GE(r.final_coverage, 0.8);
    EXPECT_TRUE(r.final_ds_index == 1 || r.final_ds_index == 2) << r.final_ds_index;  // switching cycles 1, 2
  }
}

TEST(Maps, AThirdCoordinateStepDoublingAndCoefficientsItLacksAreRefusedByName) {
  const Environment env = square_map(10.0);
  RunParams p = small_run(10.0);
  p.system = system_index("chirikov");
  p.ds_index = 1;
  EXPECT_EQ(validate_run(p, env), "");
  EXPECT_EQ(system_dimension(p.system), 2);
  EXPECT_TRUE(system_is_map(p.system));
  EXPECT_FALSE(system_is_map(system_index("lorenz")));
  p.ds_index = 3;
  std::string e = validate_run(p, env);
  EXPECT_TRUE(chaosweep::test::has(e, "ds_index = 3 but system = chirikov has two coordinates")) << e;
  p.ds_index = 2;
  p.ic_z = 0.5;
  e = validate_run(p, env);
  EXPECT_TRUE(chaosweep::test::has(e, "ic_z = 0.5 but system = chirikov has two coordinates")) << e;
  p.ic_z = 0.0;  // what its rows record: `run --from` sets it back
  EXPECT_EQ(validate_run(p, env), "");
  p.integrator = Integrator::rk4_doubling;
  e = validate_run(p, env);
  EXPECT_TRUE(chaosweep::test::has(e, "integrator = rk4-doubling but system = chirikov is a map")) << e;
  p.integrator = Integrator::rk4;
  p.sys_b = 1.0;
  e = validate_run(p, env);
  EXPECT_TRUE(chaosweep::test::has(e, "sys_b is set but system = chirikov has 1 coefficients (K as sys_a..a)")) << e;
}
