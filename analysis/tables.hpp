#pragma once
// The tables `chaosweep table NAME` prints, each built from result rows.
#include <map>
#include <string>
#include <vector>

#include "analysis/result_set.hpp"
#include "analysis/text_table.hpp"

namespace chaosweep {

struct TableOptions {
  std::vector<std::string> by;      // group columns (best, summary); empty: the table's default
  std::vector<std::string> params;  // parameter columns (best); empty: those that vary in a group
  int top = 5;                      // tuples per group (best)
  std::string paper;                // table1: CSV of the paper's values (row,paper_ct,paper_pr)
  int bins = 360;                   // seed002: orientation bins
  std::string grid;                 // tune: a grid search's result file, its best beside the tuner's
};

// table1: per Table 1 case (the run's label, else size/SR/env/variant), the
//   best parameter tuple (c, DSindex, f) by median CT, its CT, improvement
//   over the same map's original Arnold, and PR; seed 000's layout.
// best: the top-k parameter tuples per group by median CT.
// summary: per group, runs, ok rate and CT quantiles.
TextTable make_table(const std::string& name, const ResultSet& rs, const TableOptions& opt);
const std::vector<std::string>& table_names();
// The columns table `name` reads with `opt` (ResultSet::load's `columns`
// and `if_varying`); all: it reads every column.
struct TableColumns {
  bool all = true;
  std::vector<std::string> columns, if_varying;
};
TableColumns table_columns(const std::string& name, const TableOptions& opt);
// seed001: the Chebyshev map's own numbers (Lyapunov exponents, v(xy)) beside
// seed 001's; computed, so it reads no result file.
bool table_needs_results(const std::string& name);

// The paper's Table 1 values by row (row,paper_ct,paper_pr); none for an
// empty path.
std::map<std::string, std::pair<double, double>> read_paper(const std::string& path);
// A case's technique set ("original", "IS", "MZ+SC", "Logistic map", ...).
std::string technique(const ResultSet& rs, const std::vector<std::size_t>& rows);
// Whether every run has a non-empty label.
bool every_run_labelled(const ResultSet& rs);
// A label as a number (NaN when it is not one).
double label_number(const std::string& s);

// A parameter tuple's score: the median coverage time of its runs, a run
// that did not reach the target counting as infinitely long (so a tuple
// whose runs mostly time out never wins).
double tuple_score(const ResultSet& rs, const std::vector<std::size_t>& rows);

}  // namespace chaosweep
