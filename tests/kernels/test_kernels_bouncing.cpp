// Kernels: seed 002 (docs/spec.md §5), the bouncing robot: cell configuration space and
// GCM step, Tarjan SCCs and persistent groups, the Markov chain's limiting
// distribution, the policy mixture (Eq. 5) and the roadmap plans (Algs. 1-2).
//
// Hand-checkable map used throughout: an empty 2 x 2 square, cell 1 m, 4 bins
// (E=0, N=1, W=2, S=3), one sample point (the centroid), step = 1 cell.
// Position cells: 0=(0,0) 1=(1,0) 2=(0,1) 3=(1,1).
// Under the 90-degree policy a forward step leaves the map exactly when the
// heading points at an outer wall; then the robot stays and turns CCW by 90:
//   (0,E)->(1,E)->bump->(1,N)->(3,N)->bump->(3,W)->(2,W)->bump->(2,S)->(0,S)->bump->(0,E)
// an 8-cycle. The other 8 configurations each lead into it in one or two
// steps and nothing leads back: (0,N)->(2,N)->(2,W); (0,W)->(0,S);
// (1,W)->(0,W); (1,S)->(1,E); (2,E)->(3,E)->(3,N); (3,S)->(1,S).
// So: 9 SCCs, one closed (the cycle), pi = 1/8 on the cycle, 0 elsewhere, and
// each position cell holds two cycle configurations: marginal 1/4 each.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "kernels/planners/bouncing/bouncing_cells.hpp"
#include "kernels/planners/bouncing/markov_chain.hpp"
#include "kernels/planners/bouncing/policy_mixture.hpp"
#include "kernels/planners/bouncing/roadmap.hpp"
#include "kernels/planners/bouncing/scc.hpp"
#include "kernels/planners/planner.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;
using namespace chaosweep::bouncing_paper;

namespace {

constexpr int E = 0, N = 1, W = 2, S = 3;

Environment square(double side) {
  Environment env;
  env.name = "square";
  env.lx = env.ly = side;
  return env;
}

CellGrid grid2x2() { return make_grid(square(2.0), 1.0, 4); }
GcmOptions centroid() { return GcmOptions{0.0, 1}; }

// The paper's Fig. 6 map is lost; N = 65880 = 183 x 360 and 1464 = 183 x 8
// say it had 183 free position cells. Ours: 15 x 15 m, 1 m cells, two
// rectangular obstacles of 18 and 24 cells (one touching nothing, one near a
// wall): 225 - 42 = 183 free cells.
Environment seed002_map() {
  Environment env;
  env.name = "seed002_15x15";
  env.lx = env.ly = 15.0;
  env.obstacles = {{3.0, 4.0, 6.0, 10.0}, {9.0, 2.0, 13.0, 8.0}};
  return env;
}

}  // namespace

TEST(Seed002Cells, GridIndexesFreeCellsAndSkipsObstacleCells) {
  const CellGrid g = make_grid(seed002_map(), 1.0, 360);
  EXPECT_EQ(g.nx, 15);
  EXPECT_EQ(g.num_free(), 183);
  EXPECT_EQ(g.num_configs(), 65880);  // the paper's N for its coverage map
  EXPECT_EQ(g.free_at(4.5, 5.5), -1);
  EXPECT_GE(g.free_at(0.5, 0.5), 0);
}

TEST(Seed002Cells, RotationSplitsUnreliablePartByBinOverlap) {
  // 5-degree bins, phi 30 +- 5, r 0.8: the +-5 interval covers bin +6 fully
  // and half of bins +5 and +7: 0.8 + 0.2*0.5, 0.2*0.25, 0.2*0.25.
  const auto o = rotation_offsets(72, 30.0, 5.0, 0.8);
  ASSERT_EQ(o.size(), 3u);
  EXPECT_EQ(o[0].first, 5);
  EXPECT_NEAR(o[0].second, 0.05, 1e-12);
  EXPECT_EQ(o[1].first, 6);
  EXPECT_NEAR(o[1].second, 0.9, 1e-12);
  EXPECT_NEAR(o[2].second, 0.05, 1e-12);
  // 315 degrees wraps to offset 63 of 72; eps 0 is always exact.
  const auto z = rotation_offsets(72, 315.0, 0.0, 0.3);
  ASSERT_EQ(z.size(), 1u);
  EXPECT_EQ(z[0].first, 63);
  EXPECT_DOUBLE_EQ(z[0].second, 1.0);
}

TEST(Seed002Cells, DriveToContactReturnsContactCellAndWallNormal) {
  Environment env = square(10.0);
  env.obstacles = {{4.0, 4.0, 6.0, 6.0}};
  const CellGrid g = make_grid(env, 1.0, 8);
  auto c = drive_to_contact(g, 1.0, 5.0, 0.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->x, 4.0, 1e-12);
  EXPECT_NEAR(c->y, 5.0, 1e-12);
  EXPECT_EQ(c->normal_x, -1.0);
  EXPECT_EQ(c->free, g.free_at(3.5, 5.5));
  c = drive_to_contact(g, 1.0, 5.0, 180.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->x, 0.0, 1e-12);
  EXPECT_EQ(c->normal_x, 1.0);
  EXPECT_EQ(c->free, g.free_at(0.5, 5.5));
  c = drive_to_contact(g, 5.0, 1.0, 90.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->y, 4.0, 1e-9);
  EXPECT_EQ(c->normal_y, -1.0);
}

TEST(Seed002Cells, CellMapMovesForwardOrBumpsAndRotates) {
  const CellGrid g = grid2x2();
  const CellMap m = build_cell_map(g, 90.0, 0.0, 1.0, centroid());
  auto single = [&](int from) {
    EXPECT_EQ(m.row_start[from + 1] - m.row_start[from], 1);
    return std::make_pair(m.to[m.row_start[from]], m.bump[m.row_start[from]]);
  };
  EXPECT_EQ(single(g.config(0, E)), std::make_pair(g.config(1, E), std::uint8_t{0}));
  EXPECT_EQ(single(g.config(1, E)), std::make_pair(g.config(1, N), std::uint8_t{1}));
  EXPECT_EQ(single(g.config(0, W)), std::make_pair(g.config(0, S), std::uint8_t{1}));
  // The quarter-point samples agree here (no cell edge is close).
  const CellMap q = build_cell_map(g, 90.0, 0.0, 1.0, GcmOptions{});
  EXPECT_EQ(q.to, m.to);
}

TEST(Seed002Cells, CellMapRowsAreProbabilityDistributions) {
  const CellGrid g = make_grid(seed002_map(), 1.0, 36);
  const CellMap m = build_cell_map(g, 75.0, 5.0, 0.8);
  for (int z = 0; z < m.n; ++z) {
    double s = 0.0;
    for (int e = m.row_start[z]; e < m.row_start[z + 1]; ++e) s += m.prob[e];
    ASSERT_NEAR(s, 1.0, 1e-12) << z;
  }
}

TEST(Seed002Scc, HandMapHasOneClosedEightCycleAndEightTransients) {
  const CellGrid g = grid2x2();
  const Digraph d = support_graph(transition_matrix(build_cell_map(g, 90.0, 0.0, 1.0, centroid())));
  const Scc scc = tarjan_scc(d);
  EXPECT_EQ(scc.count, 9);
  int groups = 0;
  const auto pg = persistent_groups(scc, &groups);
  EXPECT_EQ(groups, 1);
  const int cycle[] = {g.config(0, E), g.config(1, E), g.config(1, N), g.config(3, N),
                       g.config(3, W), g.config(2, W), g.config(2, S), g.config(0, S)};
  for (int c : cycle) EXPECT_EQ(pg[c], 0);
  EXPECT_EQ(std::count(pg.begin(), pg.end(), -1), 8);
}

TEST(Seed002Scc, IterativeTarjanHandlesDeepChainIntoLongCycle) {
  // 200,000 nodes in a line feeding a 200,000-node cycle: recursion would
  // need 400,000 frames. Expect 200,001 components, only the cycle closed.
  const int L = 200000, C = 200000, n = L + C;
  Digraph d;
  d.start.resize(n + 1);
  d.adj.resize(n);
  for (int v = 0; v < n; ++v) {
    d.start[v] = v;
    d.adj[v] = (v < n - 1) ? v + 1 : L;  // last cycle node closes the cycle
  }
  d.start[n] = n;
  const Scc scc = tarjan_scc(d);
  ASSERT_EQ(scc.count, L + 1);
  const int cyc = scc.component[L];
  for (int v = L; v < n; ++v) ASSERT_EQ(scc.component[v], cyc);
  EXPECT_EQ(cyc, 0);                                               // completed first: sinks get the smallest ids
  for (int v = 0; v < L; ++v) ASSERT_EQ(scc.component[v], L - v);  // reverse topological
  int groups = 0;
  const auto pg = persistent_groups(scc, &groups);
  EXPECT_EQ(groups, 1);
  EXPECT_EQ(pg[0], -1);
  EXPECT_EQ(pg[n - 1], 0);
}

TEST(Seed002Markov, HandMapLimitIsUniformOnTheCycle) {
  const CellGrid g = grid2x2();
  const Limit lim = limiting_distribution(transition_matrix(build_cell_map(g, 90.0, 0.0, 1.0, centroid())));
  ASSERT_EQ(lim.groups, 1);
  EXPECT_NEAR(lim.group_mass[0], 1.0, 1e-12);
  for (int c = 0; c < g.num_configs(); ++c) EXPECT_NEAR(lim.pi(c), lim.group[c] == 0 ? 0.125 : 0.0, 1e-12);
  const Eigen::VectorXd pos = position_marginal(g, lim.pi);
  for (int f = 0; f < 4; ++f) EXPECT_NEAR(pos(f), 0.25, 1e-12);
}

TEST(Seed002Markov, TwoGroupsShareUniformStartByAbsorptionProbability) {
  // 0 is transient: -> 1 w.p. 1/4, -> 2 w.p. 3/4. {1} absorbs (self-loop).
  // {2,3}: 2 -> 3; 3 -> 2 or 3 w.p. 1/2: stationary (1/3, 2/3).
  // p(0) = 1/4 each: m_{1} = 1/4 + 1/16 = 5/16, m_{2,3} = 1/2 + 3/16 = 11/16.
  SparseMatrix P(4, 4);
  P.insert(0, 1) = 0.25;
  P.insert(0, 2) = 0.75;
  P.insert(1, 1) = 1.0;
  P.insert(2, 3) = 1.0;
  P.insert(3, 2) = 0.5;
  P.insert(3, 3) = 0.5;
  const Limit lim = limiting_distribution(P);
  EXPECT_EQ(lim.groups, 2);
  EXPECT_NEAR(lim.pi(0), 0.0, 1e-15);
  EXPECT_NEAR(lim.pi(1), 5.0 / 16, 1e-12);
  EXPECT_NEAR(lim.pi(2), 11.0 / 48, 1e-12);
  EXPECT_NEAR(lim.pi(3), 22.0 / 48, 1e-12);
}

TEST(Seed002Markov, PeriodicAndNoisyRotationInOneCellAreUniform) {
  // A 1 x 1 map: every step bumps. phi 90, eps 0: a 4-cycle (period 4, no
  // p(n) limit; the Cesaro limit is 1/4 each). phi 90 +- 90, r 1/2: offsets
  // 0, +1, +2 w.p. 1/8, 3/4, 1/8, a circulant, so also uniform.
  const CellGrid g = make_grid(square(1.0), 1.0, 4);
  for (double eps : {0.0, 90.0}) {
    const Limit lim = limiting_distribution(transition_matrix(build_cell_map(g, 90.0, eps, 0.5)));
    EXPECT_EQ(lim.groups, 1);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(lim.pi(c), 0.25, 1e-12) << eps;
  }
}

TEST(Seed002Markov, LimitIsStationaryAndZeroOnTransientsOnObstacleMap) {
  const CellGrid g = make_grid(seed002_map(), 1.0, 36);
  const SparseMatrix P = transition_matrix(build_cell_map(g, 30.0, 5.0, 0.8));
  const Limit lim = limiting_distribution(P);
  EXPECT_NEAR(lim.pi.sum(), 1.0, 1e-9);
  EXPECT_GE(lim.pi.minCoeff(), -1e-12);
  const Eigen::VectorXd next = P.transpose() * lim.pi;
  EXPECT_LT((next - lim.pi).cwiseAbs().maxCoeff(), 1e-10);
  for (int c = 0; c < g.num_configs(); ++c) {
    if (lim.group[c] < 0) {
      ASSERT_EQ(lim.pi(c), 0.0);
    }
  }
}

TEST(Seed002Mixture, ExactOnClosedFormCases) {
  // Columns e1, e2 and target (1/2, 1/2): alpha = (1/2, 1/2), residual 0.
  Eigen::MatrixXd Pi(2, 2);
  Pi << 1, 0, 0, 1;
  Eigen::VectorXd b(2);
  b << 0.5, 0.5;
  Mixture m = best_mixture(Pi, b);
  EXPECT_NEAR(m.alpha(0), 0.5, 1e-12);
  EXPECT_NEAR(m.residual, 0.0, 1e-12);
  // Target outside the segment: (2, -1) is closest to e1 on it.
  b << 2.0, -1.0;
  m = best_mixture(Pi, b);
  EXPECT_NEAR(m.alpha(0), 1.0, 1e-12);
  EXPECT_NEAR(m.alpha(1), 0.0, 1e-12);
}

TEST(Seed002Mixture, AlphaIsOnSimplexAndBeatsEverySinglePolicy) {
  const CellGrid g = make_grid(seed002_map(), 1.0, 36);
  const std::vector<double> phis = {30.0, 75.0, 315.0};
  Eigen::MatrixXd Pi(g.num_free(), 3);
  for (int i = 0; i < 3; ++i) Pi.col(i) = policy_coverage(g, phis[i], 5.0, 0.8);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(Pi.col(i).sum(), 1.0, 1e-9);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(g.num_free(), 1.0 / g.num_free());
  const Mixture m = best_mixture(Pi, b);
  EXPECT_GE(m.alpha.minCoeff(), 0.0);
  EXPECT_NEAR(m.alpha.sum(), 1.0, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_LE(m.residual, mixture_residual(Pi, b, Eigen::VectorXd::Unit(3, i)) + 1e-15) << i;
  // No point of a coarse simplex grid does better either.
  for (int a = 0; a <= 20; ++a)
    for (int c = 0; a + c <= 20; ++c) {
      Eigen::Vector3d al(a / 20.0, c / 20.0, (20 - a - c) / 20.0);
      EXPECT_LE(m.residual, mixture_residual(Pi, b, al) + 1e-12);
    }
}

TEST(Seed002Roadmap, SinglePolicyPlanOnHandMap) {
  // (0,E) -> (3,W) with {90, 270}: 270 never turns to W at cell 3, 90 does:
  // 0 (to cell 1), bump 90 (N), 0 (to cell 3), bump 90 (W): weight 4.
  const CellGrid g = grid2x2();
  const std::vector<double> phis = {90.0, 270.0};
  const Roadmap rm = build_roadmap(g, phis, 1.0, 100.0, centroid());
  const auto p = minimum_plan(rm, g.config(0, E), g.config(3, W));
  ASSERT_TRUE(p);
  EXPECT_EQ(observation_string(*p, phis), "090\u00b0090\u00b0");
  EXPECT_DOUBLE_EQ(p->weight, 4.0);
  EXPECT_EQ(p->configs.front(), g.config(0, E));
  EXPECT_EQ(p->configs.back(), g.config(3, W));
}

TEST(Seed002Roadmap, PolicyChangeWeightTradesStepsForChanges) {
  // (0,E) -> (0,N) with {90, 180}: neither policy alone reaches (0,N); its
  // only bump predecessor is (0,S) under 180. Fewest steps (5, two changes):
  //   0, 180 (W at 1), 0, 90 (S at 0), 180 (N at 0).
  // One change only: go round the 90-cycle to (0,S) (7 steps) then 180:
  //   0 90 0 90 0 90 0 180 = 7 w1 + 1 w2.
  const CellGrid g = grid2x2();
  const std::vector<double> phis = {90.0, 180.0};
  const auto cheap = minimum_plan(build_roadmap(g, phis, 1.0, 1.0, centroid()), g.config(0, E), g.config(0, N));
  ASSERT_TRUE(cheap);
  EXPECT_EQ(observation_string(*cheap, phis), "0180\u00b0090\u00b0180\u00b0");
  EXPECT_DOUBLE_EQ(cheap->weight, 5.0);
  const auto dear = minimum_plan(build_roadmap(g, phis, 1.0, 100.0, centroid()), g.config(0, E), g.config(0, N));
  ASSERT_TRUE(dear);
  EXPECT_EQ(observation_string(*dear, phis), "090\u00b0090\u00b0090\u00b00180\u00b0");
  EXPECT_DOUBLE_EQ(dear->weight, 107.0);
}

TEST(Seed002Roadmap, AllPlansFromOneSourceMarkUnreachableAndDiagonal) {
  // With {90} only, from (0,E) exactly the 8-cycle is reachable.
  const CellGrid g = grid2x2();
  const Roadmap rm = build_roadmap(g, {90.0}, 1.0, 100.0, centroid());
  const PlanRow row = all_plans_from(rm, g.config(0, E));
  EXPECT_EQ(row.weights[g.config(0, E)], 0.0);
  EXPECT_EQ(row.plans[g.config(0, E)], "");
  EXPECT_EQ(row.weights[g.config(0, N)], -1.0);
  EXPECT_EQ(row.weights[g.config(0, S)], 7.0);
  EXPECT_EQ(row.plans[g.config(0, S)], "090\u00b0090\u00b0090\u00b00");
  EXPECT_EQ(std::count_if(row.weights.begin(), row.weights.end(), [](double w) { return w >= 0.0; }), 8);
}

// The seed002 notes' numbers (docs/seed002.md). Several seconds, so not
// in the suite; run with
//   /tmp/bbuild/tests/test_kernels --gtest_also_run_disabled_tests --gtest_filter='*Seed002Paper*'
TEST(DISABLED_Seed002Paper, MixtureForThirtySeventyFiveThreeFifteen) {
  const auto t0 = std::chrono::steady_clock::now();
  const CellGrid g = make_grid(seed002_map(), 1.0, 360);
  const std::vector<double> phis = {30.0, 75.0, 315.0};
  Eigen::MatrixXd Pi(g.num_free(), 3);
  for (int i = 0; i < 3; ++i) {
    const SparseMatrix P = transition_matrix(build_cell_map(g, phis[i], 5.0, 0.8));
    const Limit lim = limiting_distribution(P);
    Pi.col(i) = position_marginal(g, lim.pi);
    int persistent = 0;
    for (int c : lim.group) persistent += c >= 0;
    std::printf("phi %5.1f: %d persistent groups, %d persistent of %d configs, pi min/max over cells %.5f/%.5f\n",
                phis[i], lim.groups, persistent, g.num_configs(), Pi.col(i).minCoeff(), Pi.col(i).maxCoeff());
  }
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(g.num_free(), 1.0 / g.num_free());
  const Mixture m = best_mixture(Pi, b);
  std::printf("alpha = (%.8f, %.8f, %.8f), residual %.6g\n", m.alpha(0), m.alpha(1), m.alpha(2), m.residual);
  for (int i = 0; i < 3; ++i)
    std::printf("single policy %5.1f: residual %.6g\n", phis[i], mixture_residual(Pi, b, Eigen::VectorXd::Unit(3, i)));
  std::printf("%.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  EXPECT_NEAR(m.alpha.sum(), 1.0, 1e-12);
}

// ---------------------------------------- the bouncing robot in the common model

namespace {

chaosweep::RunParams bouncing(double a1, double a2, double a3) {
  chaosweep::RunParams p;
  p.planner = chaosweep::Planner::bouncing;
  p.bounce_alpha1 = a1, p.bounce_alpha2 = a2, p.bounce_alpha3 = a3;
  p.start_x = p.start_y = 1;
  p.step = 0.25;
  p.max_time = 20000;
  return p;
}

class Points : public chaosweep::TraceSink {
 public:
  void point(const chaosweep::TracePoint& q) override { pts.push_back(q); }
  std::vector<chaosweep::TracePoint> pts;
};

}  // namespace

TEST(BouncingPlanner, TheMixtureCoversTheMapAndTheRunIsAPureFunctionOfItsSeed) {
  const auto env = seed002_map();
  chaosweep::RunParams p = bouncing(0.221, 0.280, 0.499);
  const auto a = chaosweep::run_planner(p, env), b = chaosweep::run_planner(p, env);
  ASSERT_EQ(a.status, chaosweep::Status::ok) << a.message;
  EXPECT_EQ(a.coverage_time, b.coverage_time);
  EXPECT_EQ(a.reflections, b.reflections);
  EXPECT_GT(a.reflections, 10);
  p.seed = 1;
  EXPECT_NE(chaosweep::run_planner(p, env).coverage_time, a.coverage_time);
}

TEST(BouncingPlanner, NeverEntersAnObstacleOrLeavesTheMap) {
  const auto env = seed002_map();
  Points sink;
  chaosweep::run_planner(bouncing(0.221, 0.280, 0.499), env, &sink);
  ASSERT_GT(sink.pts.size(), 1000u);
  for (const auto& q : sink.pts) {
    ASSERT_TRUE(q.x > 0 && q.x < 15 && q.y > 0 && q.y < 15) << q.x << ", " << q.y;
    for (const auto& o : env.obstacles) ASSERT_FALSE(q.x >= o.x0 && q.x <= o.x1 && q.y >= o.y0 && q.y <= o.y1);
  }
}

TEST(BouncingPlanner, AnExactSinglePolicyIsPeriodicAndNeverCoversTheSquare) {
  // phi = 90 without error from heading 0 in an empty 10 m square: right to
  // the wall, up, left, down, right... one rectangle loop for ever (a
  // persistent group that is a cycle), far below 90%.
  chaosweep::RunParams p = bouncing(1, 0, 0);
  p.bounce_phi1 = 90;
  p.bounce_eps = 0;
  p.max_time = 5000;
  const auto r = chaosweep::run_planner(p, chaosweep::test::square_map(10));
  EXPECT_EQ(r.status, chaosweep::Status::timeout);
  EXPECT_LT(r.final_coverage, 0.5);
  p.bounce_alpha1 = 0;
  EXPECT_EQ(chaosweep::run_planner(p, chaosweep::test::square_map(10)).status, chaosweep::Status::invalid);
}
