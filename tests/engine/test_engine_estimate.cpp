// plan --estimate (engine/run/wall_time_estimate): a stratified sample of
// run_ids, extrapolated by the runs' work.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/run/serial_batch_evaluator.hpp"
#include "engine/run/wall_time_estimate.hpp"

using namespace chaosweep;

__extension__ using int128 = __int128;

TEST(WallTimeEstimate, CalibrationRunsAreOneFromEachEqualSliceAndRepeatable) {
  for (const auto& [runs, n] : {std::pair<std::int64_t, std::int64_t>{1000, 64}, {65, 64}, {1e12, 1024}}) {
    const auto ids = calibration_run_ids(runs, n, 7);
    ASSERT_EQ(std::int64_t(ids.size()), n);
    for (std::int64_t k = 0; k < n; ++k) {
      EXPECT_GE(ids[k], std::int64_t((int128)k * runs / n));
      EXPECT_LT(ids[k], std::int64_t((int128)(k + 1) * runs / n));
    }
    EXPECT_EQ(calibration_run_ids(runs, n, 7), ids);
    EXPECT_NE(calibration_run_ids(runs, n, 8), ids) << "the places are drawn, not fixed";
  }
  EXPECT_EQ(calibration_run_ids(5, 64, 1), (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
}

TEST(WallTimeEstimate, ExtrapolatesBySampleShareWithTheSamplingErrorOfTheWork) {
  const WallTimeEstimate e = extrapolate_wall_time(1000, 2.0, {10, 10, 10, 10});
  EXPECT_DOUBLE_EQ(e.seconds, 500.0);
  EXPECT_DOUBLE_EQ(e.low, 500.0);  // equal work: no sampling error
  EXPECT_DOUBLE_EQ(e.high, 500.0);
  const WallTimeEstimate s = extrapolate_wall_time(1000, 2.0, {5, 15, 5, 15});
  // mean 10, sd sqrt(100/3), standard error sd/2: +-2 se = +-sqrt(100/3) = 5.77 of 10.
  EXPECT_NEAR(s.low, 500.0 * (1 - std::sqrt(100.0 / 3) / 10), 1e-9);
  EXPECT_NEAR(s.high, 500.0 * (1 + std::sqrt(100.0 / 3) / 10), 1e-9);
  const WallTimeEstimate all = extrapolate_wall_time(4, 2.0, {5, 15, 5, 15});
  EXPECT_DOUBLE_EQ(all.seconds, 2.0);
  EXPECT_DOUBLE_EQ(all.low, all.high) << "every run ran: nothing was sampled";
}

TEST(WallTimeEstimate, RunsTheDrawnRunsOfASpec) {
  const SweepSpec spec = parse_sweep_spec(
      "[fixed]\nsize = 10\nsr = 2\nmax_time = 200\n[axes]\nA = { start = 0.3, "
      "stop = 0.7, num = 50 }\nB = [0.2, 0.3]\n",
      "s.toml");
  EnvironmentCache cache;
  const WallTimeEstimate e = estimate_wall_time(spec, cache, SerialBatchEvaluator(), 16);
  EXPECT_EQ(e.runs_drawn, 16);
  EXPECT_GT(e.sample_seconds, 0);
  EXPECT_DOUBLE_EQ(e.seconds, e.sample_seconds * 100 / 16);
  EXPECT_LE(e.low, e.seconds);
  EXPECT_GE(e.high, e.seconds);
}
