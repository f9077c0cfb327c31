#pragma once
// `chaosweep table tune`: per case of a tune's result file (chaosweep tune),
// the configuration it chose, its validated median CT with a bootstrap
// interval, the race runs it spent; beside it the validated best of a grid
// search (the tune's config 0, when `tune --grid` validated one) with a
// paired Wilcoxon signed-rank test of the two on the validation seeds they
// share, and with a grid file the grid's best on its own seeds and the runs
// it took.
#include <string>
#include <vector>

#include "analysis/result_set.hpp"
#include "analysis/text_table.hpp"

namespace chaosweep {

// The best parameter tuple of the runs labelled `label` in a grid's result
// set by median CT (tuple_score: timeouts count as infinitely long).
struct GridBest {
  std::vector<std::string> values;  // per parameter, as text (numbers in shortest round-trip form)
  std::vector<double> numbers;      // per parameter, NaN for a text column
  double score = 0;                 // median CT over the grid's own seeds
  std::size_t runs = 0;             // the grid's runs of that label
};
// Throws AnalysisError naming the label (no run has it) or a parameter the
// grid's file lacks.
GridBest grid_best(const ResultSet& grid, const std::string& label, const std::vector<std::string>& params);

struct TuneTableOptions {
  std::vector<std::string> params;  // the columns that make a configuration (empty: those that vary per case)
  double level = 0.95;              // of the bootstrap interval and the paired test
  int resamples = 2000;
};

// `grid`: a grid search's result set (or nullptr).
TextTable tune_table(const ResultSet& tune, const ResultSet* grid, const TuneTableOptions& opt);

// The columns tune_table reads.
std::vector<std::string> tune_table_columns();

}  // namespace chaosweep
