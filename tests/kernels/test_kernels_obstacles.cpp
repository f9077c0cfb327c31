// Obstacle geometry for maps of many obstacles (issue 18, item 5): the
// union area by a sweep, blocked cells by ranges, and the bucket
// index behind obstacle_at, near_obstacle and Eq. 8's push-out give exactly
// what the former scans of every obstacle gave (those scans are kept here as
// the reference), and the clutter generator's buckets change no map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "kernels/core/boundary.hpp"
#include "kernels/core/clutter.hpp"
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/robot_motion.hpp"
#include "kernels/math/splitmix.hpp"
#include "kernels/planners/planner.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;

namespace {

// The former obstacle_area: every cell of the coordinate grid, by its centre.
double area_by_cells(const Environment& env) {
  std::vector<double> xs, ys;
  for (const Rect& r : env.obstacles) {
    xs.insert(xs.end(), {std::clamp(r.x0, 0.0, env.lx), std::clamp(r.x1, 0.0, env.lx)});
    ys.insert(ys.end(), {std::clamp(r.y0, 0.0, env.ly), std::clamp(r.y1, 0.0, env.ly)});
  }
  std::sort(xs.begin(), xs.end());
  std::sort(ys.begin(), ys.end());
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i)
    for (std::size_t j = 0; j + 1 < ys.size(); ++j) {
      const double cx = 0.5 * (xs[i] + xs[i + 1]), cy = 0.5 * (ys[j] + ys[j + 1]);
      for (const Rect& r : env.obstacles)
        if (r.contains(cx, cy)) {
          area += (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]);
          break;
        }
    }
  return area;
}

// The former push_out_of_obstacles: every obstacle, in order, each round.
bool push_out_by_scan(const Environment& env, double fo, double& x, double& y) {
  bool moved = false;
  for (int round = 0; round < 8; ++round) {
    bool again = false;
    for (const Rect& r : env.obstacles) {
      const Rect grown{r.x0 - fo, r.y0 - fo, r.x1 + fo, r.y1 + fo};
      if (!grown.contains(x, y)) continue;
      const double to_left = x - grown.x0, to_right = grown.x1 - x;
      const double to_bottom = y - grown.y0, to_top = grown.y1 - y;
      const double m = std::min({to_left, to_right, to_bottom, to_top});
      if (m == to_left) x = grown.x0;
      else if (m == to_right) x = grown.x1;
      else if (m == to_bottom) y = grown.y0;
      else y = grown.y1;
      moved = again = true;
    }
    if (!again) break;
  }
  return moved;
}

// The former clutter generator: each attempt against every square placed.
std::vector<Rect> clutter_by_scan(double lx, double ly, const ClutterSpec& spec, double sx, double sy) {
  std::vector<Rect> out;
  std::uint64_t state = spec.seed;
  const double target = spec.occupancy * lx * ly, g = spec.gap;
  double area = 0.0;
  for (int attempt = 0; attempt < 100000 && area < target; ++attempt) {
    const double side = spec.min_side + (spec.max_side - spec.min_side) * uniform01(state);
    const double x = g + (lx - side - 2 * g) * uniform01(state);
    const double y = g + (ly - side - 2 * g) * uniform01(state);
    if (x < g || y < g || x + side > lx - g || y + side > ly - g) continue;
    const Rect r{x, y, x + side, y + side};
    const Rect grown{r.x0 - g, r.y0 - g, r.x1 + g, r.y1 + g};
    bool clear = !grown.contains(sx, sy);
    for (const Rect& o : out)
      clear = clear && !(grown.x0 < o.x1 && o.x0 < grown.x1 && grown.y0 < o.y1 && o.y0 < grown.y1);
    if (!clear) continue;
    out.push_back(r);
    area += side * side;
  }
  return out;
}

// n random rectangles on a side x side map: mostly small, some long bars,
// some sharing edges (a grid of integer corners), overlapping freely.
Environment random_map(std::uint64_t seed, int n, double side) {
  Environment env = test::square_map(side);
  std::uint64_t s = seed;
  for (int k = 0; k < n; ++k) {
    const bool on_grid = k % 3 == 0, bar = k % 17 == 0;
    double w = bar ? side * (0.2 + 0.5 * uniform01(s)) : side * 0.03 * (0.2 + uniform01(s));
    double h = bar ? side * 0.02 : side * 0.03 * (0.2 + uniform01(s));
    if (k % 2) std::swap(w, h);
    double x = (side - w) * uniform01(s), y = (side - h) * uniform01(s);
    if (on_grid)
      x = std::floor(x), y = std::floor(y), w = std::max(1.0, std::floor(w)), h = std::max(1.0, std::floor(h));
    env.obstacles.push_back({x, y, std::min(side, x + w), std::min(side, y + h)});
  }
  return env;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The maps the box tests walk: Table 1's five squares on 50 m, 25 random
// obstacles, and 400 of them indexed (the last).
std::vector<Environment> box_maps() {
  Environment five = test::square_map(
      50.0, {{6, 6, 22, 22}, {28, 6, 44, 22}, {6, 28, 22, 44}, {28, 28, 44, 44}, {23.5, 23.5, 26.5, 26.5}});
  Environment many = random_map(5, 400, 30);
  many.index_obstacles();
  return {five, random_map(6, 25, 30), many};
}

}  // namespace

TEST(ObstacleGeometry, UnionAreaEqualsTheCellByCellArea) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Environment env = random_map(seed, 60, 20);
    EXPECT_NEAR(env.obstacle_area(), area_by_cells(env), 1e-9 * env.lx * env.ly) << "seed " << seed;
  }
  // Disjoint squares: the sum of their areas; one square inside another: the outer one.
  Environment grid = test::square_map(100);
  for (int i = 0; i < 95; ++i)
    for (int j = 0; j < 95; ++j)
      grid.obstacles.push_back({i * 1.05 + 0.2, j * 1.05 + 0.2, i * 1.05 + 0.7, j * 1.05 + 0.7});
  EXPECT_NEAR(grid.obstacle_area(), 95 * 95 * 0.25, 1e-8);
  EXPECT_DOUBLE_EQ(test::square_map(10, {{1, 1, 5, 5}, {2, 2, 3, 3}}).obstacle_area(), 16.0);
  EXPECT_EQ(test::square_map(10).obstacle_area(), 0.0);
}

TEST(ObstacleGeometry, IndexedQueriesAnswerAsAScanOfEveryObstacle) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    Environment indexed = random_map(seed, 400, 30);
    const Environment scanned = indexed;  // no index: every query scans
    indexed.index_obstacles();
    ASSERT_NE(indexed.usable_index(), nullptr);
    ASSERT_EQ(scanned.usable_index(), nullptr);
    std::uint64_t s = seed * 977;
    for (int k = 0; k < 6000; ++k) {
      // Points anywhere (past the map too), and on obstacle edges and corners.
      double x = -2 + 34 * uniform01(s), y = -2 + 34 * uniform01(s);
      if (k % 4 == 0) {
        const Rect& r = indexed.obstacles[std::size_t(k / 4) % indexed.obstacles.size()];
        x = k % 8 == 0 ? r.x0 : r.x1;
        y = k % 16 < 8 ? r.y0 : 0.5 * (r.y0 + r.y1);
      }
      ASSERT_EQ(indexed.obstacle_at(x, y), scanned.obstacle_at(x, y)) << x << ", " << y;
      for (double fo : {0.1, 0.5, 3.0, 40.0}) {  // 40 m: wider than the buckets, a scan
        ASSERT_EQ(indexed.near_obstacle(x, y, fo), scanned.near_obstacle(x, y, fo)) << x << ", " << y << " fo " << fo;
        double xi = x, yi = y, xs = x, ys = y;
        const bool mi = push_out_of_obstacles(indexed, fo, xi, yi);
        const bool ms = push_out_by_scan(scanned, fo, xs, ys);
        ASSERT_EQ(mi, ms) << x << ", " << y << " fo " << fo;
        ASSERT_TRUE(same_bits(xi, xs) && same_bits(yi, ys)) << x << ", " << y << " fo " << fo;
      }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(indexed.obstacle_at(nan, 1), -1);
    EXPECT_FALSE(indexed.near_obstacle(1, nan, 0.5));
    // Cells: blocked by their centres.
    for (double cell : {0.37, 1.0, 2.5}) {
      const CoverageGrid grid(indexed, cell);
      int free = 0;
      for (int j = 0; j < grid.ny(); ++j)
        for (int i = 0; i < grid.nx(); ++i) {
          const double cx = 0.5 * (i * cell + std::min((i + 1) * cell, 30.0));
          const double cy = 0.5 * (j * cell + std::min((j + 1) * cell, 30.0));
          const bool blocked = scanned.obstacle_at(cx, cy) >= 0;
          ASSERT_EQ(grid.at(i, j) == CoverageGrid::blocked, blocked) << i << ", " << j << " cell " << cell;
          free += !blocked;
        }
      EXPECT_EQ(grid.free_cells(), free);
    }
  }
}

// An obstacle is cut off a box on the side whose new edge lies farthest
// from the robot (a lane leaves its box through such an edge), not on the
// side that keeps the most area: here the cut above the obstacle keeps 3x
// the area, 1 m from the robot; the cut left of it lies 3 m away.
TEST(ObstacleGeometry, ABoxCutsAnObstacleOffFarthestFromTheRobot) {
  const Environment env = test::square_map(50.0, {{13, 0, 40, 9}});
  const ObstacleBox b = obstacle_box(env, 0.0, 10.0, 10.0, {0, 0, 50, 50}, 100.0, false);
  EXPECT_EQ(b.box.x0, 0.0);
  EXPECT_EQ(b.box.x1, 13.0);
  EXPECT_EQ(b.box.y0, 0.0);
  EXPECT_EQ(b.box.y1, 50.0);
  // The robot above it, nearer the top face: the cut above, the box to the band's edges.
  const ObstacleBox above = obstacle_box(env, 0.0, 30.0, 12.0, {0, 0, 50, 50}, 100.0, false);
  EXPECT_EQ(above.box.y0, 9.0);
  EXPECT_EQ(above.box.x0, 0.0);
  EXPECT_EQ(above.box.x1, 50.0);
}

// The lanes apply Eq. 8 themselves inside a lane's obstacle box
// (kernels/lanes): for every point P of the box, keep_out_of_obstacles must
// move P only when the box's near obstacle (grown by fo) holds it, and then
// once, onto (or about) that rectangle's face of least penetration, whenever
// the point it reaches is in the box too. Checked on Table 1's five squares and on maps of
// overlapping obstacles scanned and indexed (400: the index's queries), at
// points anywhere in the box, on its edges and corners, on the faces and
// just inside them.
TEST(ObstacleGeometry, InAnObstacleBoxEq8IsAtMostOnePushOntoTheNearObstacle) {
  const std::vector<Environment> maps = box_maps();
  ASSERT_NE(maps.back().usable_index(), nullptr);
  std::uint64_t s = 41;
  int boxes = 0, empty = 0, pushes = 0, still = 0;
  for (const Environment& env : maps)
    for (const double fo : {0.0, 0.5, 2.0})
      for (const bool with_near : {true, false}) {
        const Rect band{fo, fo, env.lx - fo, env.ly - fo};
        for (int k = 0; k < 150; ++k) {
          // A robot where the planner leaves one: anywhere in the band, pushed out (most of them).
          double x = band.x0 + (band.x1 - band.x0) * uniform01(s), y = band.y0 + (band.y1 - band.y0) * uniform01(s);
          if (k % 5) keep_out_of_obstacles(env, fo, false, x, y);
          const double reach = 1 + 10 * uniform01(s);
          const bool mirror = k % 3 == 2;  // obstacle_response = "mirror": reflected about the face
          const ObstacleBox b = obstacle_box(env, fo, x, y, band, reach, with_near);
          if (b.box.x0 > b.box.x1) {
            ++empty;
            continue;
          }
          ++boxes;
          ASSERT_TRUE(b.box.contains_closed(x, y)) << x << ", " << y;
          ASSERT_TRUE(b.box.x0 >= band.x0 && b.box.x1 <= band.x1 && b.box.y0 >= band.y0 && b.box.y1 <= band.y1);
          ASSERT_TRUE(b.box.x0 >= x - reach && b.box.x1 <= x + reach && b.box.y0 >= y - reach && b.box.y1 <= y + reach);
          if (!with_near) {
            ASSERT_TRUE(b.near.x0 > b.near.x1);
          }
          const Rect& g = b.near;
          const auto in_box_x = [&](double u) { return std::clamp(u, b.box.x0, b.box.x1); };
          const auto in_box_y = [&](double u) { return std::clamp(u, b.box.y0, b.box.y1); };
          for (int q = 0; q < 60; ++q) {
            double px = b.box.x0 + (b.box.x1 - b.box.x0) * uniform01(s);
            double py = b.box.y0 + (b.box.y1 - b.box.y0) * uniform01(s);
            if (q % 6 == 1) px = q % 12 < 6 ? b.box.x0 : b.box.x1;  // the box's edges and corners
            if (q % 6 == 2) py = q % 12 < 6 ? b.box.y0 : b.box.y1;
            if (g.x0 <= g.x1 && q % 6 >= 3) {  // on near's faces, and just inside them
              const double fx = q % 12 < 6 ? g.x0 : g.x1, fy = q % 12 < 6 ? g.y0 : g.y1;
              const double cx = 0.5 * (g.x0 + g.x1), cy = 0.5 * (g.y0 + g.y1);
              if (q % 6 == 3) px = in_box_x(fx);
              if (q % 6 == 4) py = in_box_y(fy);
              if (q % 6 == 5) px = in_box_x(std::nextafter(fx, cx)), py = in_box_y(std::nextafter(fy, cy));
            }
            double qx = px, qy = py;
            const ObstacleHit hit = keep_out_of_obstacles(env, fo, mirror, qx, qy);
            if (!g.contains(px, py)) {
              ASSERT_FALSE(hit.moved) << px << ", " << py << " fo " << fo;
              ++still;
              continue;
            }
            // move_to_face onto (mirror: about) near's face of least penetration.
            const double to_left = px - g.x0, to_right = g.x1 - px, to_bottom = py - g.y0, to_top = g.y1 - py;
            const double m = std::min({to_left, to_right, to_bottom, to_top});
            double ex = px, ey = py;
            const auto place = [mirror](double& u, double face) { u = mirror ? (face + face) - u : face; };
            if (m == to_left) place(ex, g.x0);
            else if (m == to_right) place(ex, g.x1);
            else if (m == to_bottom) place(ey, g.y0);
            else place(ey, g.y1);
            if (!b.box.contains_closed(ex, ey)) continue;  // the lanes leave it to the planner
            ASSERT_TRUE(same_bits(qx, ex) && same_bits(qy, ey)) << px << ", " << py << " fo " << fo;
            ASSERT_EQ(hit.x_faces + hit.y_faces, 1);
            ++pushes;
          }
        }
      }
  EXPECT_GT(boxes, 1000);
  EXPECT_GT(pushes, 1000);
  EXPECT_GT(still, 10000);
  EXPECT_GT(empty, 0);  // a robot inside a grown rectangle that is not the nearest, or between two of them
}

// RobotMotion skips the pass over the obstacles while the robot is in a box
// that meets no obstacle's margin: every move still ends where the pass after
// every move puts it, bit for bit (Eq. 7 at the walls, then Eq. 8 read as
// obstacle_response, then the clamp into the map after a push).
TEST(ObstacleGeometry, TheRobotsClearBoxesChangeNoMove) {
  const std::vector<Environment> maps = box_maps();
  ASSERT_NE(maps.back().usable_index(), nullptr);
  std::uint64_t s = 7;
  long moves = 0, pushed = 0;
  for (const Environment& env : maps)
    for (const double fo : {0.5, 2.0})
      for (const ObstacleResponse response :
           {ObstacleResponse::push, ObstacleResponse::mirror, ObstacleResponse::reflect}) {
        RunParams p = test::small_run(env.lx);
        p.fo = fo;
        p.obstacle_response = response;
        double x = fo + (env.lx - 2 * fo) * uniform01(s), y = fo + (env.ly - 2 * fo) * uniform01(s);
        keep_out_of_obstacles(env, fo, false, x, y);
        p.start_x = x;
        p.start_y = y;
        CoverageGrid grid(env, 1.0);
        RobotMotion robot(p, env, grid);
        const bool mirror = response != ObstacleResponse::push;
        double sx = 1, sy = 1, heading = 6.283 * uniform01(s);
        for (int i = 0; i < 20000; ++i, ++moves) {
          // A heading that turns slowly, so that the robot crosses boxes and meets obstacles.
          heading += 0.6 * (uniform01(s) - 0.5);
          const double len = i % 97 == 0 ? 5.0 : 0.05 + 0.4 * uniform01(s);
          const double dx = len * std::cos(heading), dy = len * std::sin(heading);
          robot.move(dx, dy);
          x = mirror_eq7(x + sx * dx, 0.0, env.lx, fo);
          y = mirror_eq7(y + sy * dy, 0.0, env.ly, fo);
          const ObstacleHit hit = keep_out_of_obstacles(env, fo, mirror, x, y);
          if (hit.moved) {
            ++pushed;
            if (response == ObstacleResponse::reflect && hit.x_faces % 2) sx = -sx;
            if (response == ObstacleResponse::reflect && hit.y_faces % 2) sy = -sy;
            x = std::clamp(x, 0.0, env.lx);
            y = std::clamp(y, 0.0, env.ly);
          }
          ASSERT_TRUE(same_bits(robot.x(), x) && same_bits(robot.y(), y))
              << "move " << i << ": " << robot.x() << ", " << robot.y() << " against " << x << ", " << y;
        }
      }
  EXPECT_EQ(moves, 360000);
  EXPECT_GT(pushed, 5000);  // the walk meets obstacles often enough to test the boxes' edges
}

TEST(ObstacleGeometry, ARunOnAnIndexedMapEqualsTheRunOnTheSameMapScanned) {
  Environment indexed = random_map(3, 150, 20);
  const Environment scanned = indexed;
  indexed.index_obstacles();
  for (int zoning : {0, 1}) {
    RunParams p = test::small_run(20);
    p.start_x = p.start_y = 0.05;
    p.map_zoning = zoning;
    p.max_time = 3000;
    const RunResult a = run_planner(p, indexed), b = run_planner(p, scanned);
    EXPECT_EQ(a.status, b.status);
    EXPECT_TRUE(same_bits(a.coverage_time, b.coverage_time) ||
                (std::isnan(a.coverage_time) && std::isnan(b.coverage_time)));
    EXPECT_EQ(a.steps, b.steps);
    EXPECT_EQ(a.free_cells, b.free_cells);
    EXPECT_EQ(a.visited_cells, b.visited_cells);
    EXPECT_EQ(a.transits, b.transits);
    EXPECT_TRUE(same_bits(a.final_x, b.final_x) && same_bits(a.final_y, b.final_y));
    EXPECT_TRUE(same_bits(a.t_opt, b.t_opt));
    EXPECT_GT(a.steps, 1000);
  }
}

TEST(ObstacleGeometry, TheClutterGeneratorsBucketsChangeNoMap) {
  struct Case {
    double side, occupancy, min_side, max_side, gap;
  };
  for (const Case& c : {Case{50, 0.08, 1.5, 4.0, 1.0}, Case{10, 0.3, 0.1, 0.9, 0.02}, Case{30, 0.2, 0.2, 0.5, 0.0},
                        Case{20, 0.3, 0.2, 0.4, 0.01}}) {
    for (std::uint64_t seed = 0; seed < 3; ++seed) {
      ClutterSpec spec{seed, c.occupancy, c.min_side, c.max_side, c.gap};
      const std::vector<Rect> a = generate_clutter(c.side, c.side, spec, 0.5, 0.5);
      const std::vector<Rect> b = clutter_by_scan(c.side, c.side, spec, 0.5, 0.5);
      ASSERT_EQ(a.size(), b.size()) << c.side << " seed " << seed;
      for (std::size_t k = 0; k < a.size(); ++k)
        ASSERT_TRUE(same_bits(a[k].x0, b[k].x0) && same_bits(a[k].y0, b[k].y0) && same_bits(a[k].x1, b[k].x1)) << k;
      EXPECT_LE(a.size(), std::size_t(max_clutter_attempts));
    }
  }
}

TEST(ObstacleGeometry, TheChebyshevDecompositionRefusesMoreCellsThanItCanMerge) {
  // 100 scattered obstacles cut the workplace into about 4e4 cells: a run
  // took 69 s in the merging step (200: over 300 s). Refused at once instead.
  const Environment env = random_map(5, 100, 100);
  RunParams p = test::small_run(100);
  p.planner = Planner::chebyshev;
  p.start_x = p.start_y = 0.5;
  const std::string why = validate_run(p, env);
  EXPECT_NE(why.find(" obstacles cut the workplace into "), std::string::npos) << why;
  EXPECT_NE(why.find("cells, more than the Chebyshev decomposition's 16384"), std::string::npos) << why;
  EXPECT_EQ(run_planner(p, env).status, Status::invalid);
  // A few obstacles are decomposed as before.
  EXPECT_EQ(validate_run(p, random_map(5, 10, 100)).find("cut the workplace"), std::string::npos);
}
