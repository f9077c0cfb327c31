#pragma once
// `chaosweep bench --variants`: single-thread ns per simulated step of the
// seed-000 technique variants (issue 20) on open and obstacle maps, each
// also as a ratio to original Arnold on the open map of the same size and SR.
#include <string>
#include <vector>

namespace chaosweep {

struct VariantOptions {
  int runs = 384;           // runs per cell, the same parameters in every cell
  double max_time = 20000;  // robot seconds per run at most (and max_pr = 50 as Table 1)
  // Every cell measured this many times: in each round the cells of one map
  // size and SR (both maps, every variant) run back to back, their order
  // rotated from round to round, so that a slow phase of a shared machine
  // falls on a ratio's two cells alike.
  int rounds = 3;
};

struct VariantCell {
  double size = 0, sr = 0;
  std::string env;      // "open" or "five_squares"
  std::string variant;  // original, IS, SC, MZ, IS+MZ+SC, logistic
  int runs = 0;
  double arnold_steps = 0;            // RunResult::steps summed (Logistic points for the logistic planner)
  double transit_points = 0;          // RunResult::transit_points summed (MapZoning transits)
  std::vector<double> round_seconds;  // wall time of the cell's runs in each round, one thread, setup included
  double seconds = 0;                 // their median
  double ns_per_step = 0;             // 1e9 seconds / (arnold_steps + transit_points)
  // ns_per_step / that of original on the open map of the same size and SR,
  // taken in each round: the median of the rounds' ratios, their least and
  // greatest.
  double ratio = 0, ratio_min = 0, ratio_max = 0;
};

struct VariantsReport {
  VariantOptions options;
  std::string target;  // the lane width that ran
  std::vector<VariantCell> cells;
  double seconds = 0;  // the whole measurement
};

// The cells' names, in the order reported.
const std::vector<std::string>& bench_variant_names();

VariantsReport run_variants_bench(const VariantOptions& o);
std::string variants_json(const VariantsReport& r);
std::string variants_text(const VariantsReport& r);

}  // namespace chaosweep
