#pragma once
// The figures `chaosweep figure NAME` draws. Each computes its data from
// result rows, writes it as CSV beside the image (same name, .csv) and
// renders the image with MathGL (plot.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/plot.hpp"
#include "analysis/result_set.hpp"

namespace chaosweep {

struct FigureOptions {
  std::string x, y;                             // heatmap: the two axes
  std::string stat = "min";                     // heatmap, line: statistic (grouping.hpp)
  bool stat_default = true;                     // --stat not given (line then takes the median)
  std::vector<double> mark;                     // fig6a/fig6b: the marked (A, B, C)
  LabelSide mark_label = LabelSide::automatic;  // fig6a/fig6b: where the mark's label goes
  double bound = 0;                             // fig6b: time bound, s (0: the runs' max_time)
  std::vector<std::int64_t> runs;               // trajectory, coverage: run ids
  std::string by;                               // coverage: one run (the median) per value of this column;
                                                // ct_distribution: group columns, comma-separated
  int bins = 360;                               // seed002_limit: orientation bins
  int policy = 0;                               // seed002_limit: 0 the mixture, i the i-th policy alone
  ImageSize size;
};

struct FigureOutput {
  std::string image, csv;
  std::vector<std::string> lines;  // findings to print (e.g. the marked tuple's percentile)
};

// fig6a: minimum CT over B as a colour map over (A, C), the marked tuple's (A, C) shown.
// fig6b: share of (A, B, C) tuples reaching the target within each time bound,
//        the marked tuple's CT and percentile shown.
// heatmap: a statistic of CT (or ok rate, runs) over two swept axes.
// line: a statistic of any column over another, one line per --by value.
// trajectory: one run's path over its map, from a replay of its parameters.
// coverage: coverage vs time for several runs.
// ct_distribution: per file and group of --by, the ECDF of coverage time (ct_distribution.hpp).
// leaderboard: per planner (--by, as `table leaderboard`), the share of its runs within each PR
//        over every map, in the leaderboard's order (leaderboard_figure.hpp).
// cheb_histogram: the Chebyshev orbit's histogram, raw and arcsine-transformed.
// cheb_lyapunov: the Chebyshev map's Lyapunov exponent over k, raw and transformed.
FigureOutput make_figure(const std::string& name, const ResultSet& rs, const FigureOptions& opt,
                         const std::string& image_path);
const std::vector<std::string>& figure_names();
// cheb_histogram, cheb_lyapunov: seed 001's map analysis, computed; no result file.
bool figure_needs_results(const std::string& name);
// seed002_limit: the best bouncing-policy mixture's limiting distribution (computed).

// ct_distribution: a curve per file (and group of --by), so it reads each
// file on its own, --where applied to each; make_figure draws it for merged
// rows as one set named "results".
bool figure_per_file(const std::string& name);
FigureOutput make_per_file_figure(const std::string& name, const std::vector<std::string>& files,
                                  const std::vector<std::string>& where, const FigureOptions& opt,
                                  const std::string& image_path);

// The CSV path written beside an image: the same path with .csv.
std::string csv_beside(const std::string& image_path);

}  // namespace chaosweep
