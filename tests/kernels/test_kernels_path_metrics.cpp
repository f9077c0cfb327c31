// Kernels: the path metrics every planner gets from the coverage grid
// (docs/spec.md §1, "Path metrics"): visits counted per cell entry, turns
// between successive entries, Pielou's evenness of the visits over the free
// cells, the entropy of the turns and the coverage-time area, on hand-made
// paths whose values are known, and on runs of the planners.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/metrics.hpp"
#include "kernels/planners/planner.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;
using chaosweep::test::small_run;
using chaosweep::test::square_map;

namespace {

// Marks the cells (i, j) in order, as a planner's moves would.
void walk(CoverageGrid& g, const std::vector<std::pair<int, int>>& cells) {
  for (const auto& [i, j] : cells) g.mark_cell(i, j);
}

}  // namespace

TEST(PathMetrics, EachCellOnceInALawnmowerIsPerfectlyEvenWithTwoKindsOfTurn) {
  const Environment env = square_map(4.0);
  CoverageGrid g(env, 1.0);
  // Boustrophedon over 4 x 4: east along row 0, north, west along row 1, ...
  std::vector<std::pair<int, int>> path;
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 4; ++k) path.push_back({j % 2 == 0 ? k : 3 - k, j});
  walk(g, path);
  for (std::uint32_t v : g.visits()) EXPECT_EQ(v, 1u);
  EXPECT_DOUBLE_EQ(visit_evenness(g), 1.0);
  // 15 moves, 14 turns: per row change left, left (rows 0->1) or right,
  // right (1->2), 3 x 2 = 6 turns; straight 8.
  const std::int64_t* t = g.turns();
  EXPECT_EQ(t[0], 8);  // straight
  EXPECT_EQ(t[1], 4);  // left: E->N, N->W, then at row 2->3 again
  EXPECT_EQ(t[2], 0);  // back
  EXPECT_EQ(t[3], 2);  // right: W->N, N->E
  const double p[] = {8.0 / 14, 4.0 / 14, 2.0 / 14};
  double h = 0;
  for (double q : p) h -= q * std::log2(q);
  EXPECT_NEAR(turn_entropy(g), h, 1e-15);
}

TEST(PathMetrics, StayingInACellIsNoVisitAndAStraightLineHasNoTurnEntropy) {
  const Environment env = square_map(4.0);
  CoverageGrid g(env, 1.0);
  walk(g, {{0, 0}, {0, 0}, {1, 0}, {1, 0}, {1, 0}, {2, 0}, {3, 0}});
  EXPECT_EQ(g.visits()[0], 1u);
  EXPECT_EQ(g.visits()[1], 1u);
  EXPECT_EQ(g.turns()[0], 2);  // E, E, E: two straight turns
  EXPECT_DOUBLE_EQ(turn_entropy(g), 0.0);
  // Back and forth between two cells: every turn is back.
  CoverageGrid b(env, 1.0);
  walk(b, {{0, 0}, {1, 0}, {0, 0}, {1, 0}, {0, 0}});
  EXPECT_EQ(b.visits()[0], 3u);
  EXPECT_EQ(b.visits()[1], 2u);
  EXPECT_EQ(b.turns()[2], 3);
  EXPECT_DOUBLE_EQ(turn_entropy(b), 0.0);
  // Two cells of 16 visited 3 and 2 times: H = -(0.6 ln 0.6 + 0.4 ln 0.4), J = H / ln 16.
  EXPECT_NEAR(visit_evenness(b), -(0.6 * std::log(0.6) + 0.4 * std::log(0.4)) / std::log(16.0), 1e-15);
}

TEST(PathMetrics, BlockedCellsAreNotInTheEvennessAndAJumpTakesItsLongerAxis) {
  // The obstacle's centre cells (1..2, 1..2) are blocked: 12 free cells.
  const Environment env = square_map(4.0, {{1, 1, 3, 3}});
  CoverageGrid g(env, 1.0);
  ASSERT_EQ(g.free_cells(), 12);
  walk(g, {{0, 0}, {3, 1}, {3, 3}, {0, 3}});  // jumps: east (3 > 1), north, west
  EXPECT_EQ(g.turns()[1], 2);                 // E->N, N->W: left, left
  EXPECT_NEAR(visit_evenness(g), std::log(4.0) / std::log(12.0), 1e-15);
}

TEST(PathMetrics, EveryPlannerReportsThemInItsResult) {
  for (Planner planner : {Planner::arnold, Planner::logistic, Planner::chebyshev, Planner::bouncing,
                          Planner::contraction, Planner::random_walk, Planner::random_bounce, Planner::lawnmower}) {
    RunParams p = small_run();
    p.planner = planner;
    const RunResult r = run_planner(p, square_map(p.size_x));
    ASSERT_NE(r.status, Status::invalid) << r.message;
    EXPECT_GT(r.visit_evenness, 0.3) << to_string(planner);
    EXPECT_LT(r.visit_evenness, 1.0) << to_string(planner);
    EXPECT_GT(r.turn_entropy, 0.1) << to_string(planner);
    EXPECT_LE(r.turn_entropy, 2.0) << to_string(planner);
    // The mean first-visit time of the cells dc needs lies between 0 and
    // the time the last of them was visited (CT, or the budget).
    EXPECT_GT(r.coverage_area, 0.0) << to_string(planner);
    const double last = r.status == Status::ok ? r.coverage_time : r.t_end;
    EXPECT_LT(r.coverage_area, std::max(last, run_budget(p, r.t_opt)) / r.t_opt) << to_string(planner);
    if (r.status == Status::ok) {
      EXPECT_LT(r.coverage_area, r.pr) << to_string(planner);
    }
  }
}

TEST(PathMetrics, CoverageAreaIsTheMeanFirstVisitTimeOfTheCellsTheTargetNeeds) {
  const Environment env = square_map(4.0);
  CoverageGrid g(env, 1.0);
  g.count_cover_times(5);  // dc needs 5 of the 16 cells
  g.mark_cell(0, 0);
  g.note_time(0.0);  // the start
  g.mark_cell(1, 0);
  g.mark_cell(2, 0);
  g.note_time(3.0);  // two cells in one move, both at its end
  g.mark_cell(2, 0);
  g.note_time(4.0);  // a cell seen before counts once, at its first visit
  g.mark_cell(3, 0);
  g.note_time(6.0);
  EXPECT_EQ(g.cover_noted(), 4);
  EXPECT_DOUBLE_EQ(g.cover_time_sum(), 0.0 + 3.0 + 3.0 + 6.0);
  // One cell short: counted at the budget (40), over 5 cells and T_opt 8.
  EXPECT_DOUBLE_EQ(coverage_area(g, 7.0, 40.0, 8.0), (12.0 + 40.0) / (5 * 8.0));
  // A cell marked after the last note counts at the run's end.
  g.mark_cell(3, 1);
  EXPECT_DOUBLE_EQ(coverage_area(g, 7.0, 40.0, 8.0), (12.0 + 7.0) / (5 * 8.0));
  g.note_time(7.5);
  // Cells beyond the target's count nothing.
  g.mark_cell(3, 2);
  g.note_time(9.0);
  EXPECT_EQ(g.cover_noted(), 5);
  EXPECT_DOUBLE_EQ(coverage_area(g, 9.0, 40.0, 8.0), (12.0 + 7.5) / (5 * 8.0));
  // A lawnmower that enters one new cell per second covers n cells with a
  // mean first-visit time (n - 1) / 2 s: near T_opt / 2 (T_opt = n s here).
  CoverageGrid m(env, 1.0);
  m.count_cover_times(16);
  for (int k = 0; k < 16; ++k) {
    m.mark_cell(k % 4, k / 4);
    m.note_time(double(k));
  }
  EXPECT_DOUBLE_EQ(coverage_area(m, 15.0, 320.0, 16.0), 7.5 / 16.0);
}

TEST(PathMetrics, TheLawnmowerBaselineCoversAtASteadyPaceSoItsCoverageAreaIsAboutOneHalf) {
  RunParams p = small_run(10.0);
  p.planner = Planner::lawnmower;
  p.start_x = p.start_y = 0.5;
  const RunResult r = run_planner(p, square_map(10.0));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_NEAR(r.pr, 1.0, 0.02);
  // One new cell per metre from the start's centre: the i-th at about
  // i - 0.5 s, a mean of about (n - 1) / 2 s over n = 90 cells, T_opt = 90 s.
  EXPECT_NEAR(r.coverage_area, 0.49, 0.01);
}

// visit_evenness computes each count's term once (counts below 1024) and
// sums the cells' terms in row order: bit for bit the sum of
// (n / total) ln(n / total) over the free cells, for counts that repeat,
// counts from 1 up to past the memo's end, and cells never entered.
TEST(PathMetrics, EvennessIsTheCellByCellSumBitForBitWhateverTheCounts) {
  const Environment env = square_map(40.0, {{10, 10, 20, 20}});
  CoverageGrid g(env, 1.0);
  // Back and forth between two neighbours of each row: counts 1 .. 3000.
  for (int j = 0; j < g.ny(); j += 3) {
    const int i = (j * 7) % (g.nx() - 1);
    if (g.at(i, j) == CoverageGrid::blocked || g.at(i + 1, j) == CoverageGrid::blocked) continue;
    const int n = j == 0 ? 3000 : j % 2 ? 1 + j : 1023 + j % 4;
    for (int k = 0; k < n; ++k) g.mark_cell(i + (k % 2), j);
  }
  double total = 0, h = 0;
  std::vector<double> counts;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i)
      if (g.at(i, j) != CoverageGrid::blocked) counts.push_back(double(g.visits()[std::size_t(j) * g.nx() + i]));
  for (double n : counts) total += n;
  for (double n : counts)
    if (n > 0) h -= (n / total) * std::log(n / total);
  ASSERT_GT(*std::max_element(counts.begin(), counts.end()), 1024.0);
  EXPECT_EQ(visit_evenness(g), h / std::log(double(g.free_cells())));
}
