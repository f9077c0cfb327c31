// Kernels: per-map setup shared by runs (issue 20). MapZoning's zone counts
// kept by the grid as cells are marked, equal to a rescan; the setup cache
// keyed by everything a setup depends on, bounded and thread-safe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/setup_cache.hpp"
#include "kernels/math/splitmix.hpp"
#include "kernels/planners/arnold/planner_run.hpp"
#include "kernels/planners/arnold/zones.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;
using chaosweep::test::small_run;
using chaosweep::test::square_map;

namespace {

void expect_same_zones(const std::vector<ZoneInfo>& a, const std::vector<ZoneInfo>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].index, b[k].index);
    EXPECT_EQ(a[k].free_cells, b[k].free_cells) << "zone " << k;
    EXPECT_EQ(a[k].visited_cells, b[k].visited_cells) << "zone " << k;
    EXPECT_EQ(a[k].has_goal, b[k].has_goal);
    EXPECT_EQ(a[k].goal_x, b[k].goal_x);
    EXPECT_EQ(a[k].goal_y, b[k].goal_y);
    EXPECT_EQ(a[k].mid_x, b[k].mid_x);
    EXPECT_EQ(a[k].mid_y, b[k].mid_y);
  }
}

// A 37 m map (zones not aligned with the 1 m cells, a clipped last column at
// sr 1.3) with two obstacles, the first ending on a column of cell centres.
Environment uneven_map() { return square_map(37.0, {{5, 5, 12.5, 9}, {20, 14.5, 26, 30}}); }

}  // namespace

TEST(ZoneCounts, KeptByTheGridEqualARescanAfterRandomCrossings) {
  const Environment env = uneven_map();
  for (double sr : {1.0, 1.3}) {
    CoverageGrid g(env, sr);
    g.mark_point(0.5, 0.5);  // visited before the counting starts
    const Zones counted(env, g, 4, 3, true, 0.5), scanned(env, g, 4, 3, true, 0.5);
    g.count_regions(counted.cell_zones(), counted.count());
    ASSERT_EQ(g.regions(), counted.cell_zones().get());
    std::uint64_t s = 20;
    double x = 0.5, y = 0.5;
    for (int k = 0; k < 3000; ++k) {
      // Segments of up to 3 m, some of them through the obstacles (blocked
      // cells are never counted), some along the walls.
      const double nx = std::clamp(x + 6 * uniform01(s) - 3, 0.0, env.lx);
      const double ny = std::clamp(y + 6 * uniform01(s) - 3, 0.0, env.ly);
      g.mark_segment(x, y, nx, ny);
      x = nx, y = ny;
      if (k % 250 == 0 || k == 2999) {
        const auto a = counted.snapshot(g), b = scanned.snapshot(g);
        expect_same_zones(a, b);
        int sum = 0;
        for (const ZoneInfo& z : a) sum += z.visited_cells;
        EXPECT_EQ(sum, g.visited_cells());
      }
    }
    EXPECT_GT(g.visited_cells(), 300);
  }
}

TEST(ZoneCounts, OnlyAMapZoningRunMakesZonesAndCountsByThem) {
  const Environment env = uneven_map();
  for (bool mz : {false, true}) {
    RunParams p = small_run(37.0);
    p.map_zoning = mz;
    CoverageGrid g(env, p.sr);
    RunResult r;
    r.t_opt = 1000;
    PlannerRun run(p, env, g, r, nullptr);
    EXPECT_EQ(g.regions() != nullptr, mz);
  }
}

TEST(SharedZones, EqualTheZonesBuiltForTheRunAndAreSharedPerKey) {
  const Environment env = uneven_map();
  const CoverageGrid g(env, 1.0);
  const auto a = shared_zones(env, g, 4, 3, true, 0.5);
  EXPECT_EQ(shared_zones(env, g, 4, 3, true, 0.5), a);  // cached: the same object
  expect_same_zones(a->snapshot(g), Zones(env, g, 4, 3, true, 0.5).snapshot(g));
  Environment renamed = env;
  renamed.name = "another name, the same map";
  EXPECT_EQ(shared_zones(renamed, g, 4, 3, true, 0.5), a);
}

TEST(SharedZones, TwoMapsOrParameterSetsNeverShareAnEntry) {
  const Environment env = uneven_map();
  const CoverageGrid g(env, 1.0);
  const auto base = shared_zones(env, g, 4, 3, true, 0.5);
  // Each differs from the first in one input the zones depend on.
  Environment moved = env;
  moved.obstacles[0].x1 = std::nextafter(12.5, 13.0);  // one ulp: now covers the centres x = 12.5
  Environment wider = env;
  wider.lx = 38.0;
  const CoverageGrid g_moved(moved, 1.0), g_wider(wider, 1.0), g_fine(env, 0.5);
  struct Case {
    const char* what;
    std::shared_ptr<const Zones> cached;
    Zones built;
    const CoverageGrid& grid;
  };
  const Case cases[] = {
      {"obstacle", shared_zones(moved, g_moved, 4, 3, true, 0.5), Zones(moved, g_moved, 4, 3, true, 0.5), g_moved},
      {"map size", shared_zones(wider, g_wider, 4, 3, true, 0.5), Zones(wider, g_wider, 4, 3, true, 0.5), g_wider},
      {"sr", shared_zones(env, g_fine, 4, 3, true, 0.5), Zones(env, g_fine, 4, 3, true, 0.5), g_fine},
      {"zones_x", shared_zones(env, g, 3, 3, true, 0.5), Zones(env, g, 3, 3, true, 0.5), g},
      {"zones_y", shared_zones(env, g, 4, 4, true, 0.5), Zones(env, g, 4, 4, true, 0.5), g},
      {"zone_goal", shared_zones(env, g, 4, 3, false, 0.5), Zones(env, g, 4, 3, false, 0.5), g},
      {"fo", shared_zones(env, g, 4, 3, true, 2.5), Zones(env, g, 4, 3, true, 2.5), g},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    EXPECT_NE(c.cached, base);
    expect_same_zones(c.cached->snapshot(c.grid), c.built.snapshot(c.grid));
  }
  // The one-ulp obstacle blocks 4 more cells of zone 1: a shared entry would have shown it.
  EXPECT_EQ(cases[0].cached->snapshot(g_moved)[1].free_cells, base->snapshot(g)[1].free_cells - 4);
}

TEST(SetupCache, KeysAreExactBytesAndTheCostBoundEvictsTheLeastRecentlyUsed) {
  SetupCache<int> cache(10);
  int made = 0;
  auto get = [&](double k, std::size_t cost) {
    return *cache.get(SetupKey().add(k), cost, [&] { return ++made, std::make_shared<const int>(int(k * 10)); });
  };
  EXPECT_EQ(get(1.0, 4), 10);
  EXPECT_EQ(get(2.0, 4), 20);
  EXPECT_EQ(get(1.0, 4), 10);  // hit: 2.0 is now the least recently used
  EXPECT_EQ(made, 2);
  EXPECT_EQ(get(-0.0, 1), 0);  // -0 and 0 are different bytes: different keys
  EXPECT_EQ(get(0.0, 1), 0);
  EXPECT_EQ(made, 4);
  EXPECT_EQ(get(3.0, 4), 30);  // 14 > 10: evicts 2.0 (and not 1.0)
  EXPECT_EQ(cache.size(), 4u);
  EXPECT_EQ(get(1.0, 4), 10);
  EXPECT_EQ(made, 5);
  EXPECT_EQ(get(2.0, 4), 20);
  EXPECT_EQ(made, 6);
  EXPECT_EQ(get(9.0, 11), 90);  // costs more than the bound: built, not kept
  EXPECT_EQ(get(9.0, 11), 90);
  EXPECT_EQ(made, 8);
  EXPECT_EQ(cache.builds(), 6u);
}

TEST(SetupCache, ThreadsGetTheValueOfTheirKey) {
  SetupCache<int> cache(3);  // fewer entries than keys: lookups, builds and evictions race
  auto worker = [&](int seed, bool* ok) {
    std::uint64_t s = std::uint64_t(seed);
    for (int k = 0; k < 2000; ++k) {
      const int key = int(splitmix64(s) % 5);
      const auto v = cache.get(SetupKey().add(key), 1, [&] { return std::make_shared<const int>(key * 7); });
      *ok &= *v == key * 7;
    }
  };
  bool ok1 = true, ok2 = true;
  std::thread t1(worker, 1, &ok1), t2(worker, 2, &ok2);
  t1.join();
  t2.join();
  EXPECT_TRUE(ok1 && ok2);
  EXPECT_LE(cache.size(), 3u);
}
