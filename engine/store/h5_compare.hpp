#pragma once
// `chaosweep compare A.h5 B.h5`: runs aligned on their parameters (run_id for
// the same spec, param_hash otherwise), every output column compared with
// tolerances, and per group a rank test of the coverage-time distributions.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace chaosweep {

struct CompareOptions {
  double rtol = 0.0, atol = 0.0;  // |a - b| <= atol + rtol * |b| for float columns
  int show = 10;                  // differences listed in the report
  // Memory bounds (docs/store.md, "Readers"): rows per block read (0: the
  // reader's default), and rows of B held at once when the files are not
  // both in run_id order (they are then aligned in passes over a part of
  // the keys each); `force_passes` (tests) aligns in passes even so.
  std::size_t block_rows = 0, part_rows = std::size_t(1) << 19;
  bool force_passes = false;
};

struct CompareReport {
  std::int64_t aligned = 0, identical = 0, changed = 0, missing = 0, extra = 0;
  bool by_run_id = true;
  // How the runs were aligned: passes over each file (1 when both are in
  // run_id order and merged as they stream), and the most rows of B held at
  // once beyond the blocks being read (0 when streamed).
  std::int64_t passes = 0, rows_held = 0;
  std::vector<std::string> details;  // first differences: run, column, values
  std::vector<std::string> schema;   // columns only one file has (other engine versions)
  struct Group {
    std::string key;
    std::int64_t ok_a, ok_b;
    double median_a, median_b, p_value;  // Mann-Whitney U, two-sided
  };
  std::vector<Group> groups;
  bool same() const { return changed == 0 && missing == 0 && extra == 0 && schema.empty(); }
  std::string text() const;
};

CompareReport compare_results(const std::string& a, const std::string& b, const CompareOptions& opt);

// Two-sided p-value of the Mann-Whitney U test (normal approximation with tie
// correction); NaN when a sample is empty.
double mann_whitney_p(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace chaosweep
