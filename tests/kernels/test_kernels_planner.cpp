// Kernels: the control techniques of seed 000 (Algorithms 1, 2 and 4) on
// small hand-made cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "kernels/core/boundary.hpp"
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/planners/arnold/control.hpp"
#include "kernels/planners/arnold/planner_run.hpp"
#include "kernels/planners/arnold/transit.hpp"
#include "kernels/planners/arnold/zones.hpp"
#include "kernels/planners/planner.hpp"
#include "kernels/systems/logistic_map.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;
using chaosweep::test::small_run;
using chaosweep::test::square_map;

namespace {

// Marks `n` free cells of zone (a, b) of a 2 x 2 zoning of an 8 m map (1 m cells).
void visit(CoverageGrid& g, int a, int b, int n) {
  for (int k = 0; k < n; ++k) g.mark_cell(a * 4 + k % 4, b * 4 + k / 4);
}

std::vector<int> indices(const std::vector<ZoneInfo>& zones) {
  std::vector<int> out;
  for (const ZoneInfo& z : zones) out.push_back(z.index);
  return out;
}

struct Recorder : TraceSink {
  std::vector<TracePoint> points;
  void point(const TracePoint& p) override { points.push_back(p); }
};

// A PlannerRun on a hand-made map, for driving single mechanisms.
struct Harness {
  Harness(const RunParams& params, Environment e) : p(params), env(std::move(e)), grid(env, p.sr) {
    r.t_opt = 1000;
    run = std::make_unique<PlannerRun>(p, env, grid, r, &trace);
  }
  RunParams p;
  Environment env;
  CoverageGrid grid;
  RunResult r;
  Recorder trace;
  std::unique_ptr<PlannerRun> run;

  bool trace_avoids_obstacles() const {
    for (const TracePoint& t : trace.points)
      if (env.obstacle_at(t.x, t.y) >= 0) return false;
    return true;
  }
};

// A long budget so that mechanisms, not the clock, end what the tests drive.
RunParams mechanism_run(double side) {
  RunParams p = small_run(side);
  p.max_time = 1e6;
  return p;
}

// MapZoning on a 20 m map of 2 x 2 zones with paper-literal goals (the
// midpoints (5, 5), (15, 5), (5, 15), (15, 15)), th = 3, the robot at (1, 1).
RunParams midpoint_zoning_run() {
  RunParams p = mechanism_run(20.0);
  p.th = 3;
  p.zones_x = p.zones_y = 2;
  p.zone_goal = ZoneGoal::midpoint;
  p.start_x = p.start_y = 1.0;
  return p;
}

// Obstacles over every one of those midpoints.
Environment blocked_midpoints() {
  return square_map(20.0, {{3, 3, 7, 7}, {13, 3, 17, 7}, {3, 13, 7, 17}, {13, 13, 17, 17}});
}

}  // namespace

// ------------------------------------------------------------------ zones

TEST(ZoneOrder, WithoutObstaclesLowestDensityFirstTiesByDistance) {
  const Environment env = square_map(8.0);
  CoverageGrid g(env, 1.0);
  const Zones zones(env, g, 2, 2, true, 0.5);
  visit(g, 0, 0, 16);  // zone 0: the robot's, full
  visit(g, 1, 0, 8);   // zone 1: density 0.5
  visit(g, 0, 1, 2);   // zone 2: density 0.125
  visit(g, 1, 1, 2);   // zone 3: density 0.125, farther from the robot at (1, 1)
  const auto order = zone_order(zones.snapshot(g), zones.zone_of(1, 1), 1, 1.5, false);
  EXPECT_EQ(indices(order), (std::vector<int>{2, 3, 1}));  // the robot's zone is no candidate
}

TEST(ZoneOrder, WithObstaclesNearestFirstTiesByDensity) {
  const Environment env = square_map(8.0, {{3.9, 3.9, 4.1, 4.1}});  // tiny: no cell centre inside
  CoverageGrid g(env, 1.0);
  const Zones zones(env, g, 2, 2, true, 0.5);
  visit(g, 1, 0, 12);
  visit(g, 0, 1, 1);
  // Robot at (2, 2) in zone 0: zones 1 and 2 are equally near (midpoints (6,2)
  // and (2,6)), zone 3 farthest whatever its density.
  const auto order = zone_order(zones.snapshot(g), 0, 2.0, 2.0, true);
  EXPECT_EQ(indices(order), (std::vector<int>{2, 1, 3}));
}

TEST(ZoneOrder, TheParameterPicksTheRankingOnEveryMap) {
  // auto: by the map (Section 3.2); density (Section 3.2.1) and distance
  // (Algorithm 2, lines 5-9) whatever the map.
  EXPECT_FALSE(zones_distance_first(ZoneOrder::automatic, false));
  EXPECT_TRUE(zones_distance_first(ZoneOrder::automatic, true));
  for (bool obstacles : {false, true}) {
    EXPECT_FALSE(zones_distance_first(ZoneOrder::density, obstacles));
    EXPECT_TRUE(zones_distance_first(ZoneOrder::distance, obstacles));
  }
  const Environment env = square_map(8.0);
  CoverageGrid g(env, 1.0);
  const Zones zones(env, g, 2, 2, true, 0.5);
  visit(g, 1, 0, 8);  // the two zones next to the robot's, half covered
  visit(g, 0, 1, 8);
  const auto z = zones.snapshot(g);
  EXPECT_EQ(indices(zone_order(z, 0, 1.0, 1.0, zones_distance_first(ZoneOrder::density, false))),
            (std::vector<int>{3, 1, 2}));  // the empty far zone first
  EXPECT_EQ(indices(zone_order(z, 0, 1.0, 1.0, zones_distance_first(ZoneOrder::distance, false))),
            (std::vector<int>{1, 2, 3}));  // the near ones first
}

TEST(ZoneOrder, ZonesWithoutFreeCellsAreNoCandidates) {
  const Environment env = square_map(8.0, {{4, 4, 8, 8}});  // zone 3 fully blocked
  CoverageGrid g(env, 1.0);
  const Zones zones(env, g, 2, 2, true, 0.5);
  const auto order = zone_order(zones.snapshot(g), 0, 1.0, 1.0, true);
  EXPECT_EQ(indices(order), (std::vector<int>{1, 2}));
}

TEST(ZoneGoal, IsTheMidpointOrTheNearestClearFreeCell) {
  const Environment env = square_map(8.0, {{1, 1, 3, 3}});  // covers zone 0's midpoint (2, 2)
  const CoverageGrid g(env, 1.0);
  const auto free_goals = Zones(env, g, 2, 2, true, 0.5).snapshot(g);
  EXPECT_TRUE(free_goals[0].has_goal);
  EXPECT_FALSE(env.obstacle_at(free_goals[0].goal_x, free_goals[0].goal_y) >= 0);
  EXPECT_NEAR(std::hypot(free_goals[0].goal_x - 2, free_goals[0].goal_y - 2), std::hypot(1.5, 0.5), 1e-12);
  EXPECT_EQ(free_goals[1].goal_x, 6.0);  // clear midpoints stay
  const auto literal = Zones(env, g, 2, 2, false, 0.5).snapshot(g);
  EXPECT_EQ(literal[0].goal_x, 2.0);
  EXPECT_EQ(literal[0].goal_y, 2.0);
}

// ---------------------------------------------------------------- transits

// The orbit a run draws, its own first iterates then the shared blocks, is
// the Logistic map stepped and its heading's cosine and sine taken one
// iterate at a time, on whichever branch each draw asks for: for two runs
// out of step (the one first at a block leaves a mark and draws on, the
// other builds it) and a third that reads the blocks.
TEST(LogisticOrbit, DrawsTheMapsIteratesAndHeadingsWhoeverBuiltTheBlocks) {
  const int draws = 20000;
  for (const double x0 : {0.1, 0.123456789, 0.75}) {  // 0.75 = 1 - 1/r: degenerate at once
    struct Expected {
      double x;
      bool ok;
      double cos, sin;
    };
    std::vector<Expected> expected;
    double x = x0;
    for (int n = 0; n < draws; ++n) {
      const bool right = (n * 7 / 5) % 2 == 0;
      x = 4.0 * x * (1.0 - x);
      const bool ok = x > 0.0 && x <= 1.0 && x != 0.75;
      const double th = std::numbers::pi * x + (right ? -0.5 : 0.5) * std::numbers::pi;
      expected.push_back({x, ok, std::cos(th), std::sin(th)});  // the transits': the C library's
    }
    LogisticOrbit first(4.0, x0), second(4.0, x0), third(4.0, x0);
    const auto check = [&](LogisticOrbit& o, int n, const char* who) {
      const LogisticOrbit::Heading h = o.next((n * 7 / 5) % 2 == 0);
      const Expected& e = expected[std::size_t(n)];
      ASSERT_EQ(h.x, e.x) << who << ", x0 " << x0 << ", n " << n;
      ASSERT_EQ(h.ok, e.ok) << who << ", x0 " << x0 << ", n " << n;
      ASSERT_EQ(h.cos, e.cos) << who << ", x0 " << x0 << ", n " << n;
      ASSERT_EQ(h.sin, e.sin) << who << ", x0 " << x0 << ", n " << n;
      ASSERT_EQ(o.x(), e.x);
    };
    for (int n = 0; n < draws; ++n) {
      check(n % 3 == 0 ? second : first, n, "ahead");
      check(n % 3 == 0 ? first : second, n, "behind");
    }
    for (int n = 0; n < draws; ++n) check(third, n, "third");
  }
}

// headings(n, ...) gives what n calls of next() give, whatever spans it
// reads the shared blocks in: chunks of many sizes across the run's own
// draws and the blocks' ends, a second orbit building the blocks the first
// only marked, a third reading them; and it stops at the first degenerate
// iterate as next() says it, the orbit's place and x() where next() leaves
// them (r 2.5 from 0.1 lands on its fixed point inside a shared block).
TEST(LogisticOrbit, HeadingsInSpansDrawWhatNextDraws) {
  for (const auto& orbit : {std::tuple{4.0, 0.2345678, false}, std::tuple{2.5, 0.1, true}}) {
    const auto [r, x0, degenerate] = orbit;
    const double rate = r;  // the lambda below names it (clang captures no structured binding)
    const int draws = 9000;
    struct Drawn {
      double x, cos, sin;
      bool ok;
    };
    std::vector<Drawn> expected;  // by next(), one at a time
    LogisticOrbit reference(r, x0);
    const auto right = [](int n) { return (n / 97) % 2 == 0; };  // the branch a chunk starting at n asks for
    const int sizes[] = {1, 5, 37, 200, 3, 1000, 64};
    for (int n = 0, c = 0; n < draws; ++c) {
      const int size = std::min(sizes[c % 7], draws - n);
      for (int k = 0; k < size; ++k) {
        const LogisticOrbit::Heading h = reference.next(right(n));
        expected.push_back({h.x, h.cos, h.sin, h.ok});
      }
      n += size;
    }
    int stop = draws;
    for (int n = 0; n < draws; ++n)
      if (!expected[std::size_t(n)].ok) {
        stop = n;
        break;
      }
    if (degenerate) ASSERT_GT(stop, 40) << "the degenerate iterate must lie in a shared block";
    else ASSERT_EQ(stop, draws);
    for (const char* who : {"builder", "reader"}) {
      LogisticOrbit o(r, x0);
      int n = 0;
      for (int c = 0; n < stop; ++c) {
        const int size = std::min(sizes[c % 7], draws - n);
        int k = 0;
        const bool ok = o.headings(size, right(n), [&](double cos, double sin) {
          const Drawn& e = expected[std::size_t(n + k)];
          ASSERT_EQ(cos, e.cos) << who << ", r " << rate << ", n " << n + k;
          ASSERT_EQ(sin, e.sin) << who << ", r " << rate << ", n " << n + k;
          ++k;
        });
        if (!ok) {
          ASSERT_EQ(n + k, stop) << who << ", r " << r;
          ASSERT_EQ(o.x(), expected[std::size_t(stop)].x) << who << ", r " << r;
          // The orbit goes on after the degenerate iterate as next()'s would.
          ASSERT_EQ(o.next(true).x, expected[std::size_t(stop) + 1].x) << who << ", r " << r;
          break;
        }
        ASSERT_EQ(k, size);
        n += size;
        ASSERT_EQ(o.x(), expected[std::size_t(n) - 1].x) << who << ", r " << r << ", n " << n;
      }
      ASSERT_EQ(degenerate, n < draws) << who << ", r " << r;
    }
  }
}

TEST(TransitPath, StartsAtTheRobotAndEndsAtTheMidpoint) {
  LogisticOrbit map(4.0, 0.1);
  const Point start{3.0, 4.0}, goal{17.0, 9.5};
  const auto path = transit_path(start, goal, 1.0, 0.1, map);
  const double d = std::hypot(14.0, 5.5);
  ASSERT_EQ(path.size(), std::size_t(std::floor(d / 0.1)) + 1);
  EXPECT_EQ(path.front().x, start.x);
  EXPECT_EQ(path.front().y, start.y);
  EXPECT_EQ(path.back().x, goal.x);
  EXPECT_EQ(path.back().y, goal.y);
  // The Logistic wiggle stays: the path is not the straight line.
  double off_line = 0;
  for (const Point& p : path)
    off_line = std::max(off_line, std::fabs((p.x - start.x) * 5.5 - (p.y - start.y) * 14.0) / d);
  EXPECT_GT(off_line, 0.1);
}

TEST(TransitPath, HeadsRightwardsWhenTheGoalIsToTheRight) {
  // m = 2: one pure Logistic step, then the goal. The Eq. 4 branch moves the
  // robot towards the goal's side: -pi/2 rightwards, +pi/2 leftwards.
  LogisticOrbit a(4.0, 0.1), b(4.0, 0.1);
  const auto right = transit_path({10, 10}, {10.05, 10}, 1.0, 0.1, a);
  const auto left = transit_path({10, 10}, {9.95, 10}, 1.0, 0.1, b);
  ASSERT_EQ(right.size(), 2u);
  ASSERT_EQ(left.size(), 2u);
  EXPECT_EQ(a.x(), b.x());  // same Logistic state, different branch
  double c_right, c_left, s;
  LogisticMap::heading(a.x(), LogisticMap::rightwards, c_right, s);
  LogisticMap::heading(a.x(), LogisticMap::leftwards, c_left, s);
  EXPECT_GT(c_right, 0.0);
  EXPECT_LT(c_left, 0.0);
}

TEST(Transit, ReachesAReachableGoal) {
  RunParams p = mechanism_run(20.0);
  const Environment env = square_map(20.0);
  Harness h(p, env);
  PlannerRun& run = *h.run;
  RunResult& r = h.r;
  EXPECT_TRUE(run.transit_to({15.0, 12.0}));
  EXPECT_EQ(run.position().x, 15.0);
  EXPECT_EQ(run.position().y, 12.0);
  EXPECT_EQ(r.transit_attempts, 0);
  EXPECT_NEAR(run.time(), r.transit_points * p.dt_c, 1e-9);  // each mapped point costs dt_c
}

TEST(Transit, ByDistanceTakesThePathLengthAtSpeedV) {
  RunParams p = mechanism_run(20.0);
  p.transit_time = TransitTime::distance;
  p.v = 2.0;
  Harness h(p, square_map(20.0));
  ASSERT_TRUE(h.run->transit_to({15.0, 12.0}));
  double length = 0;
  for (std::size_t i = 1; i < h.trace.points.size(); ++i)
    length += std::hypot(h.trace.points[i].x - h.trace.points[i - 1].x, h.trace.points[i].y - h.trace.points[i - 1].y);
  EXPECT_NEAR(h.run->time(), length / p.v, 1e-9);
  // Eq. 6's correction stretches the Logistic steps of v dt_c: by points the
  // transit would run faster than v.
  EXPECT_GT(h.run->time(), h.r.transit_points * p.dt_c);
}

TEST(Transit, IsRebuiltAtObstaclesAndGivesUpAfterThAttempts) {
  RunParams p = mechanism_run(20.0);
  p.th = 4;
  const Environment env = square_map(20.0, {{8, 8, 12, 12}});
  Harness h(p, env);
  PlannerRun& run = *h.run;
  RunResult& r = h.r;
  EXPECT_FALSE(run.transit_to({10.0, 10.0}));  // the goal lies inside the obstacle
  EXPECT_EQ(r.transit_attempts, 4);
  EXPECT_TRUE(h.trace_avoids_obstacles());
}

TEST(Transit, AroundAnObstacleIsRebuiltFromThePushedOutPointAndArrives) {
  RunParams p = mechanism_run(20.0);
  p.th = 50;
  p.start_x = 2.0;
  p.start_y = 10.5;
  const Environment env = square_map(20.0, {{9.5, 9.5, 10.5, 10.5}});  // a 1 m block on the straight line
  Harness h(p, env);
  PlannerRun& run = *h.run;
  RunResult& r = h.r;
  ASSERT_TRUE(run.transit_to({18.0, 10.5}));
  EXPECT_GE(r.transit_attempts, 2);  // it met the obstacle and was rebuilt, more than once
  EXPECT_LT(r.transit_attempts, 50);
  EXPECT_EQ(run.position().x, 18.0);
  EXPECT_EQ(run.position().y, 10.5);
  EXPECT_TRUE(h.trace_avoids_obstacles());
}

TEST(Transit, AHitPointIsPushedOntoTheLineAtFoOrMirroredAboutIt) {
  // The transit above under each obstacle_response: push puts a hit point on
  // the obstacle grown by fo (Eq. 8 as printed), mirror reflects it about
  // that line, so it lands beyond the line by its penetration, never on it.
  RunParams p = mechanism_run(20.0);
  p.th = 50;
  p.start_x = 2.0;
  p.start_y = 10.5;
  const Environment env = square_map(20.0, {{9.5, 9.5, 10.5, 10.5}});
  const double lo = 9.5 - p.fo, hi = 10.5 + p.fo;  // the grown obstacle
  auto on_grown_face = [&](const TracePoint& t) {
    const bool x_in = t.x >= lo && t.x <= hi, y_in = t.y >= lo && t.y <= hi;
    return (x_in && (t.y == lo || t.y == hi)) || (y_in && (t.x == lo || t.x == hi));
  };
  for (ObstacleResponse response : {ObstacleResponse::push, ObstacleResponse::mirror}) {
    p.obstacle_response = response;
    Harness h(p, env);
    ASSERT_TRUE(h.run->transit_to({18.0, 10.5}));
    ASSERT_GE(h.r.transit_attempts, 1);
    EXPECT_TRUE(h.trace_avoids_obstacles());
    const auto on_face = std::count_if(h.trace.points.begin(), h.trace.points.end(), on_grown_face);
    if (response == ObstacleResponse::push) EXPECT_GE(on_face, h.r.transit_attempts);
    else EXPECT_EQ(on_face, 0);
  }
}

TEST(Transit, ReusingTheRemainingLogisticPointsKeepsThePathsLength) {
  // The Transit test above, with Algorithm 4's re-plan as printed: after a
  // hit at point i the remaining m - i + 1 Logistic points are mapped anew,
  // so the transit walks exactly the m - 1 points of its first plan
  // (m = floor(16 m / 0.1 m) + 1), however often it was rebuilt.
  RunParams p = mechanism_run(20.0);
  p.th = 50;
  p.start_x = 2.0;
  p.start_y = 10.5;
  const Environment env = square_map(20.0, {{9.5, 9.5, 10.5, 10.5}});
  for (TransitReplan replan : {TransitReplan::reuse, TransitReplan::fresh}) {
    p.transit_replan = replan;
    Harness h(p, env);
    ASSERT_TRUE(h.run->transit_to({18.0, 10.5}));
    EXPECT_GE(h.r.transit_attempts, 1);
    EXPECT_EQ(h.run->position().x, 18.0);
    EXPECT_TRUE(h.trace_avoids_obstacles());
    if (replan == TransitReplan::reuse) EXPECT_EQ(h.r.transit_points, 160);
    else EXPECT_GT(h.r.transit_points, 160);  // each rebuild plans the rest anew
  }
}

// Point for point, a transit rebuilt at an obstacle walks what its plans
// give: Eq. 6 and 7 of the plan in force, Eq. 8 at a hit, then the next
// plan (the rest of the Logistic points mapped anew, or a fresh path): no
// point mapped under the plan before (say, mapped ahead, as a tried chunked
// walk did) may be walked after a rebuild. (A trace walks every point on
// the full path; QuietPointsGiveTheTracedRunsResults holds the quiet walk
// to it.)
TEST(Transit, EveryPointIsItsPlansPointAcrossRebuilds) {
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  RunParams p = mechanism_run(20.0);
  p.th = 50;
  p.start_x = 2.0;
  p.start_y = 10.5;
  const Environment env = square_map(20.0, {{5.5, 10.0, 6.5, 11.0}, {9.5, 9.5, 10.5, 10.5}, {13.5, 10.0, 14.5, 11.0}});
  const Point goal{18.0, 10.5};
  for (TransitReplan replan : {TransitReplan::reuse, TransitReplan::fresh}) {
    p.transit_replan = replan;
    Harness h(p, env);
    const Point start = h.run->position();
    ASSERT_TRUE(h.run->transit_to(goal)) << h.r.transit_attempts << " attempts";
    LogisticOrbit orbit = initial_logistic(p);  // the transits' own, from its start
    std::vector<Point> P;
    ASSERT_TRUE(logistic_positions(start, goal, p.v, p.dt_c, orbit, P));
    Eq6Map eq6(P, 0, start, goal);
    std::vector<Point> want;
    int hits = 0;
    for (std::size_t k = 1; k < P.size(); ++k) {
      const Point q = eq6.at(P, k);
      double x = mirror_eq7(q.x, 0.0, 20.0, p.fo), y = mirror_eq7(q.y, 0.0, 20.0, p.fo);
      const bool blocked = env.obstacle_at(x, y) >= 0;
      if (blocked) keep_out_of_obstacles(env, p.fo, p.obstacle_response != ObstacleResponse::push, x, y);
      want.push_back({x, y});
      if (!blocked) continue;
      ++hits;
      if (replan == TransitReplan::reuse && k + 1 < P.size()) {
        eq6 = Eq6Map(P, k, {x, y}, goal);
      } else {
        ASSERT_TRUE(logistic_positions({x, y}, goal, p.v, p.dt_c, orbit, P));
        eq6 = Eq6Map(P, 0, {x, y}, goal);
        k = 0;
      }
    }
    std::vector<Point> got;
    for (const TracePoint& t : h.trace.points)
      if (t.kind == SegmentKind::transit) got.push_back({t.x, t.y});
    const std::string what = replan == TransitReplan::reuse ? "reuse" : "fresh";
    ASSERT_EQ(got.size(), want.size()) << what;
    for (std::size_t n = 0; n < got.size(); ++n) {
      ASSERT_EQ(bits(got[n].x), bits(want[n].x)) << what << ", point " << n;
      ASSERT_EQ(bits(got[n].y), bits(want[n].y)) << what << ", point " << n;
    }
    ASSERT_GE(hits, 2) << what << ": " << hits << " hits";  // rebuilt more than once
    EXPECT_EQ(h.r.transit_attempts, std::int64_t(hits)) << what;
  }
}

TEST(MapZoning, DropsUnreachableZonesAndRaisesThWhenAllFail) {
  RunParams p = midpoint_zoning_run();
  p.dnh = 5;
  // Obstacles over every zone midpoint: each transit fails after th attempts
  // (the robot's own zone, which changes as it moves, is never a candidate).
  Harness h(p, blocked_midpoints());
  PlannerRun& run = *h.run;
  RunResult& r = h.r;
  run.map_zoning();
  EXPECT_GE(r.zones_dropped, 3);
  EXPECT_EQ(r.transits, 0);
  EXPECT_EQ(r.transit_attempts, 3 * r.zones_dropped);  // th attempts per dropped zone
  EXPECT_EQ(run.th(), 3 + 5);                          // every zone failed: th += dnh
}

TEST(MapZoning, LogisticResetDropRestartsTheLogisticMapWhenAZoneIsDropped) {
  RunParams p = midpoint_zoning_run();
  for (LogisticReset reset : {LogisticReset::never, LogisticReset::drop}) {
    p.logistic_reset = reset;
    Harness h(p, blocked_midpoints());
    h.run->map_zoning();  // every zone is dropped, the last one after its transit
    ASSERT_GE(h.r.zones_dropped, 3);
    if (reset == LogisticReset::drop) EXPECT_EQ(h.run->logistic_state(), p.logistic_x0);
    else EXPECT_NE(h.run->logistic_state(), p.logistic_x0);
  }
}

TEST(MapZoning, AFailedZoneIsDroppedAndTheNextOneTried) {
  const RunParams p = midpoint_zoning_run();
  // Only zone 1's midpoint (15, 5), the nearest candidate, is blocked.
  const Environment env = square_map(20.0, {{13, 3, 17, 7}});
  Harness h(p, env);
  PlannerRun& run = *h.run;
  RunResult& r = h.r;
  run.map_zoning();
  EXPECT_EQ(r.zones_dropped, 1);
  EXPECT_EQ(r.transits, 1);
  EXPECT_EQ(r.transit_attempts, 3);
  EXPECT_EQ(run.th(), 3);
}

// ----------------------------------------------------- Algorithm 1 switches

TEST(Eq5, KeepsExploringOnlyWhileTheSegmentFindsEnoughNewCells) {
  // c_n/c_nn = 10/100 = 0.1 against c * c_u/c_T = c * 0.5.
  EXPECT_TRUE(eq5_keep_exploring(10, 100, 500, 1000, 0.2));    // 0.1 >= 0.1
  EXPECT_FALSE(eq5_keep_exploring(10, 100, 500, 1000, 0.25));  // 0.1 < 0.125
  EXPECT_FALSE(eq5_keep_exploring(0, 40, 1, 1000, 0.05));      // nothing new: zone
  EXPECT_TRUE(eq5_keep_exploring(0, 40, 1, 1000, 0.0));        // c = 0: never zone
}

TEST(IndexSwitching, CyclesDsIndex) {
  EXPECT_EQ(next_ds_index(1), 2);
  EXPECT_EQ(next_ds_index(2), 3);
  EXPECT_EQ(next_ds_index(3), 1);
  EXPECT_EQ(next_ds_index(1, 2), 2);  // a two-coordinate map (Henon)
  EXPECT_EQ(next_ds_index(2, 2), 1);
}

TEST(IndexSwitching, SwitchesWhenASegmentAddsNoCell) {
  // Frozen Arnold state (A = B = C = 0) with heading z = 0: the robot runs
  // into the right wall and stays there. Switching to y = 1 rad frees it.
  RunParams p = small_run(20.0);
  p.A = p.B = p.C = 0;
  p.niter = 100;
  p.max_time = 300;
  p.dc = 1.0;
  const RunResult fixed = run_planner(p, square_map(20.0));
  p.index_switching = 1;
  const RunResult switching = run_planner(p, square_map(20.0));
  EXPECT_EQ(fixed.index_switches, 0);
  EXPECT_GE(switching.index_switches, 2);  // z -> x (still stuck) -> y
  EXPECT_GT(switching.visited_cells, fixed.visited_cells);
}

TEST(MapZoning, RunsWhenEq5FailsAndTransitsArrive) {
  RunParams p = small_run(50.0);
  p.map_zoning = 1;
  p.c = 1.0;
  p.dc = 0.9;
  const RunResult r = run_planner(p, square_map(50.0));
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_GT(r.zonings, 0);
  EXPECT_EQ(r.transits, r.zonings);  // no obstacles: every transit arrives
  EXPECT_GT(r.transit_points, 0);
}

// A transit walks the points that stay in a cell which marks nothing and
// meets no obstacle on a short path (transit_to; a trace turns it off, as it
// records every point): every result is the traced run's, bit for bit, on
// open maps and among obstacles, SR 1 and 4, both samplings, with runs
// that end at the budget or stuck within a transit.
TEST(Transit, QuietPointsGiveTheTracedRunsResults) {
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  int compared = 0, ended_in_transit = 0;
  long quiet_points = 0;
  for (const bool obstacles : {false, true})
    for (const double sr : {1.0, 4.0})
      for (const Sampling sampling : {Sampling::segments, Sampling::points})
        for (const int end : {0, 1, 2}) {  // dc, a budget, a stuck time
          const Environment env = obstacles ? square_map(40.0, {{10, 10, 18, 18}, {24, 22, 32, 30}}) : square_map(40.0);
          RunParams p = small_run(40.0);
          p.sr = sr;
          p.map_zoning = 1;
          p.c = 0.8;
          p.dc = 0.95;
          p.sampling = sampling;
          p.max_time = end == 1 ? 900.0 + 37.0 * sr : 0.0;
          p.stuck_time = end == 2 ? 25.0 : 0.0;
          p.niter = 150;
          Recorder trace;
          const RunResult a = run_planner(p, env, &trace), b = run_planner(p, env);
          const std::string what = std::string(obstacles ? "obstacles" : "open") + ", SR " + std::to_string(sr) + ", " +
                                   to_string(sampling) + ", end " + std::to_string(end);
          ASSERT_EQ(a.status, b.status) << what;
          EXPECT_EQ(bits(a.coverage_time), bits(b.coverage_time)) << what;
          EXPECT_EQ(bits(a.t_end), bits(b.t_end)) << what;
          EXPECT_EQ(bits(a.final_x), bits(b.final_x)) << what;
          EXPECT_EQ(bits(a.final_y), bits(b.final_y)) << what;
          EXPECT_EQ(bits(a.coverage_area), bits(b.coverage_area)) << what;
          EXPECT_EQ(bits(a.visit_evenness), bits(b.visit_evenness)) << what;
          EXPECT_EQ(bits(a.turn_entropy), bits(b.turn_entropy)) << what;
          EXPECT_EQ(a.steps, b.steps) << what;
          EXPECT_EQ(a.visited_cells, b.visited_cells) << what;
          EXPECT_EQ(a.segments, b.segments) << what;
          EXPECT_EQ(a.zonings, b.zonings) << what;
          EXPECT_EQ(a.transits, b.transits) << what;
          EXPECT_EQ(a.zones_dropped, b.zones_dropped) << what;
          EXPECT_EQ(a.transit_points, b.transit_points) << what;
          EXPECT_EQ(a.transit_attempts, b.transit_attempts) << what;
          ++compared;
          quiet_points += b.transit_points;
          ended_in_transit +=
              a.status != Status::ok && !trace.points.empty() && trace.points.back().kind == SegmentKind::transit;
        }
  EXPECT_EQ(compared, 24);
  EXPECT_GT(quiet_points, 10000);
  EXPECT_GE(ended_in_transit, 2);  // the budget and the stuck time end a run within a transit too
}

// The same walk by transit_to alone, each transit starting a window of Eq.
// 5 (a segment's): the quiet points leave the touches of the window, the
// cells and the clock as the traced walk does (the robot's cell, not yet
// touched in a new window, takes the full path: a point marks it, while a
// segment would mark it on leaving it).
TEST(Transit, QuietPointsCountTheWindowsTouches) {
  for (const double sr : {1.0, 4.0})
    for (const bool obstacles : {false, true})
      for (const Sampling sampling : {Sampling::segments, Sampling::points}) {
        RunParams p = mechanism_run(40.0);
        p.sr = sr;
        p.sampling = sampling;
        const Environment env = obstacles ? square_map(40.0, {{10, 10, 18, 18}}) : square_map(40.0);
        CoverageGrid traced_grid(env, p.sr), grid(env, p.sr);
        RunResult traced_r, r;
        traced_r.t_opt = r.t_opt = 1000;
        Recorder trace;
        PlannerRun traced(p, env, traced_grid, traced_r, &trace), run(p, env, grid, r, nullptr);
        const Point goals[] = {{30, 6}, {33, 35}, {5, 30}, {21, 21}, {2, 2}};
        for (const Point g : goals) {
          traced_grid.begin_window();
          grid.begin_window();
          ASSERT_EQ(traced.transit_to(g), run.transit_to(g));
          ASSERT_EQ(grid.window_distinct(), traced_grid.window_distinct())
              << sr << " " << obstacles << " " << to_string(sampling);
          ASSERT_EQ(grid.visited_cells(), traced_grid.visited_cells());
          ASSERT_EQ(run.time(), traced.time());
          ASSERT_EQ(run.position().x, traced.position().x);
          ASSERT_EQ(run.position().y, traced.position().y);
        }
        EXPECT_GT(r.transit_points, 500);
      }
}

TEST(LogisticPlanner, CoversTheMapWithLogisticSegmentsOnly) {
  RunParams p = small_run(20.0);
  p.planner = Planner::logistic;
  p.dc = 0.6;  // the Logistic planner is slow (Table 1 row 11: PR 10)
  Recorder trace;
  const RunResult r = run_planner(p, square_map(20.0), &trace);
  EXPECT_EQ(r.status, Status::ok);
  for (std::size_t i = 1; i < trace.points.size(); ++i) ASSERT_EQ(trace.points[i].kind, SegmentKind::logistic);
}

// Eq. 4 point by point, away from the walls: the planner's own map from x0
// (jittered), its heading's cosine and sine by sincos.hpp (as its lanes
// compute them), rightwards from the left half. An ulp of a heading's cosine
// seldom shows in a position, so the path is long enough for the C
// library's to leave it (checked below).
TEST(LogisticPlanner, StepsAlongEq4WithTheKernelsSincos) {
  RunParams p = small_run(1000.0);
  p.planner = Planner::logistic;
  p.logistic_jitter = 1e-3;
  p.seed = 7;
  p.start_x = 2.0;
  p.start_y = 500.0;
  p.max_time = 500.0;  // 5000 points of 0.1 m, about 0.064 m rightwards each: in the left half, off the walls
  Recorder trace;
  const RunResult r = run_planner(p, square_map(1000.0), &trace);
  ASSERT_EQ(r.status, Status::timeout);
  ASSERT_EQ(trace.points.size(), 5001u);
  EXPECT_LT(trace.points.back().x, 500.0);
  double x = initial_logistic(p).x(), X = 2.0, Y = 500.0, libc_X = X, libc_Y = Y;
  EXPECT_NE(x, p.logistic_x0);
  bool libc_differs = false;
  for (std::size_t i = 1; i < trace.points.size(); ++i) {
    x = 4.0 * x * (1.0 - x);
    const double th = std::numbers::pi * x - 0.5 * std::numbers::pi;
    double s, c;
    sincos(th, s, c);
    X += p.dt_c * p.v * c;
    Y += p.dt_c * p.v * s;
    libc_X += p.dt_c * p.v * std::cos(th);
    libc_Y += p.dt_c * p.v * std::sin(th);
    libc_differs |= libc_X != X || libc_Y != Y;
    ASSERT_EQ(trace.points[i].x, X) << i;
    ASSERT_EQ(trace.points[i].y, Y) << i;
  }
  EXPECT_TRUE(libc_differs);
}

TEST(LogisticPlanner, AFixedPointEndsTheRunAsDiverged) {
  RunParams p = small_run(20.0);
  p.planner = Planner::logistic;
  p.logistic_x0 = 0.5;  // 0.5 -> 1 -> 0
  const RunResult r = run_planner(p, square_map(20.0));
  EXPECT_EQ(r.status, Status::diverged);
}

// A run never ends a step inside an obstacle or outside the map, for every
// technique set and obstacle response, on the Table 1 layouts (scaled to 50 m).
TEST(Planner, RobotNeverEndsAStepInsideAnObstacleOrOutsideTheMap) {
  const std::vector<Rect> five = {
      {6, 6, 22, 22}, {28, 6, 44, 22}, {6, 28, 22, 44}, {28, 28, 44, 44}, {23.5, 23.5, 26.5, 26.5}};
  const std::vector<Rect> one = {{15, 15, 35, 35}};
  for (const auto& obstacles : {five, one})
    for (int variant = 0; variant < 7; ++variant) {
      RunParams p = small_run(50.0);
      if (variant == 5) p.obstacle_response = ObstacleResponse::mirror;
      if (variant == 6) p.obstacle_response = ObstacleResponse::reflect, p.map_zoning = 1;
      p.start_x = 15;
      p.start_y = 3;
      p.max_time = 4000;
      p.index_switching = variant == 1 || variant == 3;
      p.map_zoning = p.map_zoning || (variant >= 2 && variant <= 4);
      p.c = 0.8;
      p.f = variant == 4 ? 3.0 : 1.0;
      const Environment env = square_map(50.0, obstacles);
      Recorder trace;
      const RunResult r = run_planner(p, env, &trace);
      ASSERT_NE(r.status, Status::invalid) << r.message;
      for (const TracePoint& t : trace.points) {
        ASSERT_LT(env.obstacle_at(t.x, t.y), 0) << "variant " << variant << " at " << t.x << "," << t.y;
        ASSERT_TRUE(t.x >= 0 && t.x <= 50 && t.y >= 0 && t.y <= 50) << t.x << "," << t.y;
      }
    }
}

TEST(ChaoticSpread, IcJitterGivesDifferentRunsForDifferentSeeds) {
  RunParams p = small_run(20.0);
  p.ic_jitter = 1e-6;
  p.seed = 1;
  const RunResult a = run_planner(p, square_map(20.0));
  const RunResult a2 = run_planner(p, square_map(20.0));
  p.seed = 2;
  const RunResult b = run_planner(p, square_map(20.0));
  EXPECT_EQ(a.coverage_time, a2.coverage_time);  // same seed, same run
  EXPECT_NE(a.coverage_time, b.coverage_time);   // 1e-6 grows to metres (docs/spec.md §1)
  const Vec3<double> u0 = initial_state(p);
  EXPECT_NEAR(u0.y, 1.0, 1e-6);
  EXPECT_NE(u0.y, 1.0);
}

TEST(ChaoticSpread, LogisticJitterSamplesTheLogisticPlannerAndLeavesIcAlone) {
  RunParams p = small_run(20.0);
  p.planner = Planner::logistic;
  p.dc = 0.6;
  p.ic_jitter = 1e-6;  // no Arnold state here: only the Logistic jitter can spread these runs
  std::set<double> times;
  for (std::int64_t seed = 0; seed < 4; ++seed) {
    p.seed = seed;
    times.insert(run_planner(p, square_map(20.0)).coverage_time);
  }
  EXPECT_EQ(times.size(), 1u);
  p.logistic_jitter = 1e-6;
  times.clear();
  for (std::int64_t seed = 0; seed < 4; ++seed) {
    p.seed = seed;
    const RunResult r = run_planner(p, square_map(20.0));
    EXPECT_EQ(r.status, Status::ok);
    times.insert(r.coverage_time);
    EXPECT_NEAR(initial_logistic(p).x(), p.logistic_x0, 1e-6);
  }
  EXPECT_EQ(times.size(), 4u);
  p.seed = 3;
  const Vec3<double> u = initial_state(p);
  p.logistic_jitter = 0;
  const Vec3<double> u_without = initial_state(p);
  EXPECT_EQ(u.x, u_without.x);  // the Arnold draws do not move
  EXPECT_EQ(u.z, u_without.z);
}
