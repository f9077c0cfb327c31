// The fast paths of issue 20 give the very bits of what they replace: the
// AVX2 trig3 of the contraction planner
// (kernels/planners/contraction/trig3_fast.hpp) and the lanes' marking of
// diagonal steps (kernels/lanes/lane_integrator.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/lanes/lane_integrator.hpp"
#include "kernels/math/splitmix.hpp"
#include "kernels/planners/contraction/trig3_fast.hpp"
#include "tests/support/kernel_test_util.hpp"

using namespace chaosweep;

namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }
double pm1(std::uint64_t& s) { return 2.0 * uniform01(s) - 1.0; }

}  // namespace

// sincos<v4d> lane by lane is sincos<double>: the same trig3 from either.
TEST(FastPaths, Trig3Avx2IsTheScalarTrig3BitForBit) {
  if (!trig3_avx2_usable()) GTEST_SKIP() << "this CPU has no AVX2/FMA";
  std::uint64_t s = 3;
  for (int k = 0; k < 100000; ++k) {
    const double r = k % 5 ? 3.2 : 40.0;  // the wrapped range, and beyond it
    const Vec3<double> u{r * pm1(s), r * pm1(s), r * pm1(s)};
    const Trig3<double> a = trig3(u), b = trig3_fast(u, true);
    ASSERT_EQ(bits(a.sx), bits(b.sx));
    ASSERT_EQ(bits(a.cx), bits(b.cx));
    ASSERT_EQ(bits(a.sy), bits(b.sy));
    ASSERT_EQ(bits(a.cy), bits(b.cy));
    ASSERT_EQ(bits(a.sz), bits(b.sz));
    ASSERT_EQ(bits(a.cz), bits(b.cz));
  }
}

// The lanes' diagonal steps (mark_diagonal, LaneArrays::fast = 3) mark what
// CoverageGrid::mark_segment marks for the same segment: cells, window
// stamps and distinct count, region counts, visits, turns, the visited count
// and the coverage-time sum (one note_time per step), on random walks of
// steps into a diagonal neighbour, some through a grid corner exactly (both
// side cells, x first), over free and blocked cells, with and without a
// window.
TEST(FastPaths, DiagonalStepsMarkWhatTheSupercoverMarks) {
  std::uint64_t seed = 11;
  int corners = 0, steps = 0, covered = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const bool windowed = trial % 2 == 0;
    CoverageGrid ref(square_map(8.0, {{3.2, 3.2, 4.8, 4.8}}), 1.0), lane(square_map(8.0, {{3.2, 3.2, 4.8, 4.8}}), 1.0);
    auto regions = std::make_shared<std::vector<int>>(std::size_t(ref.nx() * ref.ny()));
    for (std::size_t k = 0; k < regions->size(); ++k) (*regions)[k] = int(k % 3);
    const long needed = 20 + trial % 25;  // some walks reach it midway, some never
    for (CoverageGrid* g : {&ref, &lane}) {
      g->count_regions(regions, 3);
      g->count_cover_times(needed);
      g->mark_point(0.5, 0.5);
      g->note_time(0.0);
    }
    LaneArrays a;
    a.lanes = 1;
    a.max_i[0] = lane.nx() - 1;
    a.max_j[0] = lane.ny() - 1;
    a.inv_cell[0] = lane.inv_cell_size();
    a.cells[0] = lane.cell_bytes();
    a.region[0] = lane.region_of_cell();
    a.region_visited[0] = lane.region_visited_counts();
    a.visits[0] = lane.visit_counts();
    a.turns[0] = lane.turn_counts();
    a.last_dir[0] = lane.last_direction();
    a.cell_k[0] = 0;
    a.visited[0] = lane.visited_cells();
    a.needed[0] = double(needed);
    a.cover_sum[0] = lane.cover_time_sum();
    a.t_last_new[0] = 0.0;
    a.window_distinct[0] = 0;
    double x = 0.5, y = 0.5;
    for (int n = 1; n <= 300; ++n) {
      if (windowed && n % 40 == 1)
        for (CoverageGrid* g : {&ref, &lane}) g->begin_window();
      a.stamp[0] = lane.window_stamps();
      a.window[0] = lane.window();
      a.window_distinct[0] = lane.window_distinct();
      const int i = ref.cell_x(x), j = ref.cell_y(y);
      // The next cell diagonally (back from the walls); a step through the
      // corner every fifth time (from the cell's centre), else from a point
      // within 0.3 of the corner to one beyond it.
      const int si = i == 0 ? 1 : (i == ref.nx() - 1 ? -1 : (uniform01(seed) < 0.5 ? 1 : -1));
      const int sj = j == 0 ? 1 : (j == ref.ny() - 1 ? -1 : (uniform01(seed) < 0.5 ? 1 : -1));
      const double cx = si > 0 ? i + 1 : i, cy = sj > 0 ? j + 1 : j;  // the corner crossed
      double x0 = x, y0 = y, x1, y1;
      if (n % 5 == 0) {
        x0 = i + 0.5;
        y0 = j + 0.5;
        x1 = x0 + si;
        y1 = y0 + sj;
        ++corners;
      } else {
        x0 = cx - si * 0.3 * uniform01(seed);
        y0 = cy - sj * 0.3 * uniform01(seed);
        x1 = cx + si * (0.05 + 0.3 * uniform01(seed));
        y1 = cy + sj * (0.05 + 0.3 * uniform01(seed));
      }
      // The walk's start is where the last step ended: reach (x0, y0) within
      // the cell (no mark changes: the robot's own cell).
      ASSERT_EQ(ref.cell_x(x0), i);
      ASSERT_EQ(ref.cell_y(y0), j);
      const double t = 0.1 * n;
      const int visited_before = ref.visited_cells();
      ref.mark_segment(x0, y0, x1, y1);
      ref.note_time(t);
      a.X0[0] = x0;
      a.Y0[0] = y0;
      a.X[0] = x1;
      a.Y[0] = y1;
      a.t[0] = t;
      a.cell_i[0] = ref.cell_x(x1);
      a.cell_j[0] = ref.cell_y(y1);
      const unsigned done = mark_diagonal<double>(a, 1u);
      lane.set_visited_cells(int(a.visited[0]));
      lane.set_cover_time_sum(a.cover_sum[0]);
      lane.set_window_distinct(a.window_distinct[0]);
      lane.set_entry_state(a.cell_k[0], a.last_dir[0]);
      ++steps;
      // Reported when a new cell brought the count to dc (the run ends there).
      ASSERT_EQ(done != 0, ref.visited_cells() > visited_before && ref.visited_cells() >= needed)
          << "trial " << trial << ", step " << n;
      covered += done != 0;
      ASSERT_EQ(lane.visited_cells(), ref.visited_cells()) << "trial " << trial << ", step " << n;
      ASSERT_EQ(bits(lane.cover_time_sum()), bits(ref.cover_time_sum())) << "trial " << trial << ", step " << n;
      ASSERT_EQ(lane.window_distinct(), ref.window_distinct()) << "trial " << trial << ", step " << n;
      ASSERT_EQ(a.cell_k[0], long(ref.cell_y(y1)) * ref.nx() + ref.cell_x(x1));
      ASSERT_EQ(a.last_dir[0], ref.last_direction()) << "trial " << trial << ", step " << n;
      ASSERT_TRUE(std::equal(ref.turns(), ref.turns() + 4, lane.turns())) << "trial " << trial << ", step " << n;
      ASSERT_EQ(lane.visits(), ref.visits()) << "trial " << trial << ", step " << n;
      for (int z = 0; z < 3; ++z) ASSERT_EQ(lane.region_visited(z), ref.region_visited(z));
      for (int jj = 0; jj < ref.ny(); ++jj)
        for (int ii = 0; ii < ref.nx(); ++ii) ASSERT_EQ(lane.at(ii, jj), ref.at(ii, jj));
      if (windowed) {
        for (std::size_t k = 0; k < std::size_t(ref.nx() * ref.ny()); ++k)
          ASSERT_EQ(lane.window_stamps()[k], ref.window_stamps()[k]) << "trial " << trial << ", step " << n;
      }
      x = x1;
      y = y1;
    }
  }
  EXPECT_GT(corners, 1000);
  EXPECT_GT(covered, 10);  // walks that reached dc on a diagonal step
}
