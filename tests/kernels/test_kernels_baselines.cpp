// The baseline planners (docs/spec.md §7): the lawnmower's coverage time
// against its lanes' length by hand, every baseline kept in the free space,
// seeded runs pure functions of their seed, bad input named.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "kernels/core/param_table.hpp"
#include "kernels/planners/baselines/free_space.hpp"
#include "kernels/planners/baselines/random_bounce.hpp"
#include "kernels/planners/planner.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;
using chaosweep::test::has;
using chaosweep::test::square_map;

namespace {

class Points : public TraceSink {
 public:
  void point(const TracePoint& q) override { pts.push_back(q); }
  std::vector<TracePoint> pts;
};

RunParams baseline(Planner planner, double start = 0.5) {
  RunParams p;
  p.planner = planner;
  p.sr = 1;
  p.start_x = p.start_y = start;
  return p;
}

Environment map(double lx, double ly, std::vector<Rect> obstacles = {}) {
  Environment env;
  env.name = "test";
  env.lx = lx, env.ly = ly;
  env.obstacles = std::move(obstacles);
  return env;
}

// Maps with obstacles on and off the cell lines, touching walls, and a
// corridor: a free point of each is (1, 1).
std::vector<Environment> obstacle_maps() {
  return {
      square_map(20, {{6, 6, 14, 14}}),
      square_map(20, {{2.5, 2.5, 7.5, 7.5}, {12.5, 2.5, 17.5, 7.5}, {2.5, 12.5, 7.5, 17.5}, {12.5, 12.5, 17.5, 17.5}}),
      square_map(20, {{0, 4.3, 14.7, 5.6}, {5.2, 11.1, 20, 12.9}, {3.3, 15.5, 7.9, 18.1}}),
      square_map(15, {{3, 4, 6, 10}, {9, 2, 13, 8}})};
}

// Independently of the planners' own test: no point of the segment (sampled
// finely) is inside an obstacle or outside the map.
void expect_segment_free(const Environment& env, const TracePoint& a, const TracePoint& b) {
  for (int k = 0; k <= 64; ++k) {
    const double f = k / 64.0, x = a.x + f * (b.x - a.x), y = a.y + f * (b.y - a.y);
    ASSERT_TRUE(x >= 0 && x <= env.lx && y >= 0 && y <= env.ly) << x << ", " << y;
    ASSERT_LT(env.obstacle_at(x, y), 0) << "(" << x << ", " << y << ") at t = " << b.t << " in obstacle";
  }
}

// A run that must reach its dc, its trajectory to `sink` (may be null).
RunResult run_ok(const RunParams& p, const Environment& env, Points* sink = nullptr) {
  const RunResult r = run_planner(p, env, sink);
  EXPECT_EQ(r.status, Status::ok) << to_string(p.planner) << " on " << env.name << ": " << r.message;
  return r;
}

void expect_path_free(const Environment& env, const Points& sink) {
  ASSERT_GT(sink.pts.size(), 10u);
  for (std::size_t k = 1; k < sink.pts.size(); ++k) expect_segment_free(env, sink.pts[k - 1], sink.pts[k]);
}

}  // namespace

// ---------------------------------------- lawnmower

// On an open L1 x L2 map with 1 m cells from (0.5, 0.5): lanes along x
// (the longer side) through the row centres, 0.5 .. L1 - 0.5, joined by 1 m
// moves up. A cell is entered where the path crosses into it, so after the
// rows r < R - 1 (each a lane of L1 - 1 and a 1 m move up, which enters
// row r + 1 at its end cell) the last cell of row R - 1 is entered 1.5 m
// before that lane's end: CT = (R - 1) L1 + L1 - 1.5 for R full rows,
// the last lane driven towards +x. Towards -x, one move (step) more: a
// point on a cell's edge belongs to the cell of larger index, so the robot
// enters the lower one with the first move past the edge.
TEST(BaselineLawnmower, OnAnOpenMapCoversDcAtTheLengthOfItsLanes) {
  RunParams p = baseline(Planner::lawnmower);
  p.dc = 0.9;  // 90 of 100 cells: 9 rows
  RunResult r = run_planner(p, map(10, 10));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_NEAR(r.coverage_time, 8 * 10 + 10 - 1.5, 1e-9);
  EXPECT_NEAR(r.pr, 88.5 / 90.0, 1e-12);  // T_opt = 0.9 * 100 / 1
  // 48 of the 96 cells of 12 x 8: 4 rows of 12, the 4th driven towards -x.
  p.dc = 0.5;
  r = run_planner(p, map(12, 8));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_NEAR(r.coverage_time, 3 * 12 + 12 - 1.5 + p.step, 1e-9);
  // The same lanes along y on the map turned (8 x 12), at twice the speed.
  p.v = 2;
  r = run_planner(p, map(8, 12));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_NEAR(r.coverage_time, (3 * 12 + 12 - 1.5 + p.step) / 2, 1e-9);
  EXPECT_EQ(r.final_coverage, 0.5);
}

TEST(BaselineLawnmower, ReachesEveryFreeCellOfObstacleMapsWithoutEnteringAnObstacle) {
  for (const Environment& env : obstacle_maps()) {
    RunParams p = baseline(Planner::lawnmower, 1.0);
    p.dc = 1;
    Points sink;
    EXPECT_EQ(run_ok(p, env, &sink).visited_cells, run_ok(p, env).free_cells);
    expect_path_free(env, sink);
    // dc = 0.9, as the benchmark runs it: within the 1-2 T_opt of a lawnmower.
    p.dc = 0.9;
    const RunResult q = run_ok(p, env);
    EXPECT_GT(q.pr, 0.9);
    EXPECT_LT(q.pr, 1.5);
  }
}

TEST(BaselineLawnmower, IsDeterministicAndDrawsNothingFromTheSeed) {
  const Environment env = obstacle_maps()[2];
  RunParams p = baseline(Planner::lawnmower, 1.0);
  const RunResult a = run_planner(p, env);
  p.seed = 12345;
  const RunResult b = run_planner(p, env);
  ASSERT_EQ(a.status, Status::ok) << a.message;
  EXPECT_EQ(a.coverage_time, b.coverage_time);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.visit_evenness, b.visit_evenness);
}

TEST(BaselineLawnmower, CellsItCannotReachEndTheRunAsStuck) {
  // A walled-in 5 x 5 room (25 free cells of 400 - 24 - 25 blocked ones).
  const Environment env = square_map(20, {{4, 4, 11, 5}, {4, 10, 11, 11}, {4, 5, 5, 10}, {10, 5, 11, 10}});
  RunParams p = baseline(Planner::lawnmower);
  p.dc = 1;
  RunResult r = run_planner(p, env);
  EXPECT_EQ(r.status, Status::stuck);
  EXPECT_EQ(r.free_cells - r.visited_cells, 25);
  p.dc = 0.9;
  r = run_planner(p, env);
  EXPECT_EQ(r.status, Status::ok) << r.message;
}

TEST(BaselineLawnmower, RefusesAMapItsDecompositionCannotTakeNamingThePlanner) {
  std::vector<Rect> obstacles;
  for (int k = 0; k < 100; ++k) {
    const double x = 1 + 0.97 * k, y = 1 + std::fmod(37.3 * k, 97.0);
    obstacles.push_back({x, y, x + 0.5, y + 0.5});
  }
  RunParams p = baseline(Planner::lawnmower, 0.25);
  const RunResult r = run_planner(p, square_map(100, obstacles));
  EXPECT_EQ(r.status, Status::invalid);
  EXPECT_TRUE(has(r.message, "planner = lawnmower")) << r.message;
  EXPECT_TRUE(has(r.message, "more than the Chebyshev decomposition's")) << r.message;
}

// ---------------------------------------- random walk

TEST(BaselineRandomWalk, IsAPureFunctionOfItsSeedAndReachesDc) {
  RunParams p = baseline(Planner::random_walk);
  p.step = 0.5;
  p.max_pr = 1000;
  const Environment env = square_map(10);
  const RunResult a = run_planner(p, env), b = run_planner(p, env);
  ASSERT_EQ(a.status, Status::ok) << a.message;
  EXPECT_EQ(a.coverage_time, b.coverage_time);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.reflections, b.reflections);
  EXPECT_NEAR(a.coverage_time, double(a.steps) * p.step / p.v, 1e-9 * a.coverage_time);
  p.seed = 1;
  const RunResult c = run_planner(p, env);
  ASSERT_EQ(c.status, Status::ok) << c.message;
  EXPECT_NE(c.coverage_time, a.coverage_time);
}

TEST(BaselineRandomWalk, EveryMoveIsAStepLongAndStaysFree) {
  for (const Environment& env : obstacle_maps()) {
    RunParams p = baseline(Planner::random_walk, 1.0);
    p.step = 0.7;
    p.max_time = 3000;
    Points sink;
    const RunResult r = run_planner(p, env, &sink);
    ASSERT_NE(r.status, Status::invalid) << r.message;
    EXPECT_GT(r.reflections, 0);  // walls and obstacles were met, and avoided
    expect_path_free(env, sink);
    for (std::size_t k = 1; k < sink.pts.size(); ++k)
      ASSERT_NEAR(std::hypot(sink.pts[k].x - sink.pts[k - 1].x, sink.pts[k].y - sink.pts[k - 1].y), p.step, 1e-12);
  }
}

TEST(BaselineRandomWalk, HeadingsAreUniformAwayFromWalls) {
  // On a map too large for a 0.01 m walk to meet a wall, every heading
  // drawn is taken: their quadrants share the moves evenly.
  RunParams p = baseline(Planner::random_walk, 50.0);
  p.step = 0.01;
  p.max_time = 400;  // 40000 moves
  Points sink;
  run_planner(p, square_map(100), &sink);
  const double moves = double(sink.pts.size() - 1);
  ASSERT_GT(moves, 39000);
  int quadrant[4] = {0, 0, 0, 0};
  for (std::size_t k = 1; k < sink.pts.size(); ++k) {
    const double a = std::atan2(sink.pts[k].y - sink.pts[k - 1].y, sink.pts[k].x - sink.pts[k - 1].x);
    ++quadrant[int(std::floor((a + std::numbers::pi) / (std::numbers::pi / 2))) & 3];
  }
  for (int n : quadrant) EXPECT_NEAR(n, moves / 4, 4 * std::sqrt(moves * 3 / 16));  // 4 sigma of a binomial
}

TEST(BaselineRandomWalk, AStepAsLongAsTheMapIsRefusedNamingStep) {
  RunParams p = baseline(Planner::random_walk);
  p.step = 10;
  const RunResult r = run_planner(p, square_map(10));
  EXPECT_EQ(r.status, Status::invalid);
  EXPECT_TRUE(has(r.message, "step = 10")) << r.message;
  EXPECT_TRUE(has(r.message, "random_walk")) << r.message;
  p.step = 0;
  EXPECT_TRUE(has(run_planner(p, square_map(10)).message, "step = 0 is out of range"));
}

// ---------------------------------------- random bounce

TEST(BaselineRandomBounce, IsTheBouncingRobotWithAUniformTurn) {
  RunParams p = baseline(Planner::random_bounce);
  p.step = 0.25;
  const Environment env = obstacle_maps()[3];
  const RunResult a = run_planner(p, env), b = run_planner(random_bounce_as_bouncing(p), env);
  ASSERT_EQ(a.status, Status::ok) << a.message;
  EXPECT_EQ(a.coverage_time, b.coverage_time);
  EXPECT_EQ(a.reflections, b.reflections);
  EXPECT_EQ(variant_name(p), "random_bounce");
}

// The bouncing robot's contact sensor tests where a move ends: the points
// it stops at are free, but a move may cut across an obstacle's corner by
// less than a step (docs/spec.md §7), so only the points are checked here.
TEST(BaselineRandomBounce, IsAPureFunctionOfItsSeedAndStopsOnlyInTheFreeSpace) {
  for (const Environment& env : obstacle_maps()) {
    RunParams p = baseline(Planner::random_bounce, 1.0);
    p.step = 0.25;
    Points sink;
    const double ct = run_ok(p, env, &sink).coverage_time;
    EXPECT_EQ(run_planner(p, env).coverage_time, ct);
    ASSERT_GT(sink.pts.size(), 1000u);
    for (const TracePoint& q : sink.pts) {
      ASSERT_TRUE(q.x > 0 && q.x < env.lx && q.y > 0 && q.y < env.ly) << q.x << ", " << q.y;
      ASSERT_LT(env.obstacle_at(q.x, q.y), 0) << q.x << ", " << q.y;
    }
    p.seed = 7;
    EXPECT_NE(run_ok(p, env).coverage_time, ct);
  }
}

TEST(BaselineRandomBounce, LeavesTheBottomWallInAnyUpwardHeading) {
  // The heading of the first move after each bump at the bottom wall (away
  // from the corners): uniform over the headings whose move is free, so
  // each 45-degree sector of the upper half-plane takes about a quarter of
  // the upward ones. Fine cells keep the run from covering the map first.
  RunParams p = baseline(Planner::random_bounce, 5.0);
  p.step = 0.25;
  p.sr = 0.02;
  p.dc = 1;
  p.max_time = 20000;
  Points sink;
  run_planner(p, square_map(10), &sink);
  int sector[4] = {0, 0, 0, 0}, n = 0;
  for (std::size_t k = 1; k < sink.pts.size(); ++k) {
    const TracePoint &bump = sink.pts[k - 1], &q = sink.pts[k];
    if (bump.kind != SegmentKind::subgoal || q.kind == SegmentKind::subgoal) continue;
    if (bump.y > p.step || bump.x < 1 || bump.x > 9) continue;
    const double a = std::atan2(q.y - bump.y, q.x - bump.x);
    if (a <= 0) continue;  // a little below the horizontal is free too, from above the wall
    ++sector[std::min(3, int(a / (std::numbers::pi / 4)))];
    ++n;
  }
  ASSERT_GT(n, 400);
  for (int s : sector) EXPECT_GT(s, n / 6) << "of " << n;
}

// ---------------------------------------- names

TEST(BaselinePlanners, AreChoicesOfPlannerByTheirSpecNames) {
  const ParamInfo* planner = find_param("planner");
  ASSERT_NE(planner, nullptr);
  for (Planner k : {Planner::random_walk, Planner::random_bounce, Planner::lawnmower}) {
    RunParams p;
    p.planner = k;
    EXPECT_EQ(planner->choice_index(to_string(k)), double(int(k)));
    EXPECT_EQ(variant_name(p), to_string(k));
  }
  // Appended: the planners before keep their index, so their param_hash.
  EXPECT_EQ(planner->choice_index("bouncing"), 4.0);
}

TEST(BaselineFreeSpace, AMoveAlongAnObstacleEdgeIsFreeAndOneThroughItsCornerIsNot) {
  const Rect o{2, 2, 4, 4};
  EXPECT_FALSE(crosses_interior(o, 1, 2, 5, 2));         // along the bottom edge
  EXPECT_FALSE(crosses_interior(o, 1, 3, 3, 5));         // touches the corner (2, 4) only
  EXPECT_TRUE(crosses_interior(o, 1.5, 2.5, 2.5, 2.5));  // into it through its left edge
  EXPECT_TRUE(crosses_interior(o, 0, 3, 10, 3));         // straight through
  EXPECT_FALSE(crosses_interior(o, 0, 0, 1.9, 1.9));     // short of it
  const Environment env = square_map(10, {o});
  EXPECT_FALSE(move_stays_free(env, 9.5, 5, 10, 5));  // onto the wall
  EXPECT_TRUE(move_stays_free(env, 9.5, 5, 9.9, 5));
}
