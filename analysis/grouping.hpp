#pragma once
// Rows grouped by the values of key columns, and the statistics the tables
// and figures report per group.
#include <string>
#include <string_view>
#include <vector>

#include "analysis/result_set.hpp"

namespace chaosweep {

struct Group {
  std::vector<std::string> key;  // the key columns' values as text
  std::vector<double> key_num;   // the same for numeric keys (NaN for text keys)
  std::vector<std::size_t> rows;
};

// Groups `rows` by `keys` (no keys: one group of every row). Groups come in
// key order: numeric keys by value, text keys in natural order (numbers in
// the text by value: "run 2" before "run 12").
std::vector<Group> group_rows(const ResultSet& rs, const std::vector<std::string>& keys,
                              const std::vector<std::size_t>& rows);

// Text order with runs of digits compared as numbers ("a2" < "a12").
bool natural_less(std::string_view a, std::string_view b);

// The same grouping without the keys' text (cheap for a group per row):
// group g is rows[order[k]] for k in [start[g], start[g + 1]), in `rows` order.
struct RowSpans {
  std::vector<std::size_t> order, start;
  std::size_t groups() const { return start.empty() ? 0 : start.size() - 1; }
  std::vector<std::size_t> rows_of(std::size_t g, const std::vector<std::size_t>& rows) const;
};
RowSpans group_spans(const ResultSet& rs, const std::vector<std::string>& keys, const std::vector<std::size_t>& rows);

// Quantile q in [0, 1] of v by linear interpolation between order statistics
// (Hyndman-Fan type 7, numpy's default); NaN for an empty v.
double quantile(std::vector<double> v, double q);

// The statistic a table or figure reports for a set of runs, named as on the
// command line: min, median, mean, max, q1, q3 (of coverage_time over ok
// runs), ok_rate (share of runs with status ok), runs.
double group_statistic(const ResultSet& rs, const std::vector<std::size_t>& rows, const std::string& stat,
                       const std::string& column = "coverage_time");
const std::vector<std::string>& statistic_names();

// min, q1, median, mean, q3 or max of any values (NaN for none); throws
// AnalysisError naming those for another name.
double value_statistic(std::vector<double> v, const std::string& stat);

// Splits "a,b,c" into its items (empty items dropped).
std::vector<std::string> split_list(const std::string& s);

}  // namespace chaosweep
