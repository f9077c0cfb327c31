#pragma once
// `chaosweep figure ct_distribution A.h5 [B.h5 ...]`: per result file and
// group, the empirical distribution (ECDF) of coverage time, so two planners
// or two engine versions can be compared at a glance. Each curve is the
// share of all its runs that reached the target by time t: it tops out at
// the ok share, the runs that missed the target never count as reached.
#include <string>
#include <vector>

#include "analysis/figures.hpp"
#include "analysis/result_set.hpp"

namespace chaosweep {

struct LabelledResults {
  std::string label;  // names the file in the legend and the CSV
  ResultSet rs;
};

// Short distinct names for files: the stems, or, where stems repeat, the
// parent folder and stem, or else the whole path.
std::vector<std::string> file_labels(const std::vector<std::string>& paths);

// An ECDF as a line: from (x0, 0) a step up of 100 / runs % at each of the
// sorted values (the runs that reached the target), then flat to x_end (the
// rest never arrive). Shared by ct_distribution and figure leaderboard.
LineSeries ecdf_steps(const std::vector<double>& sorted, std::size_t runs, double x0, double x_end);

// At most this many curves (files x groups of --by) in one figure.
constexpr std::size_t ct_distribution_max_curves = 12;

// opt.by: the group columns, comma-separated (empty: one group per file).
// Writes the CSV beside the image: the group keys, label, runs, ok,
// not_ok_share, coverage_time, cumulative_share (one row per ok run, in CT
// order; a group without ok runs gets one row with coverage_time "-").
FigureOutput ct_distribution(const std::vector<LabelledResults>& sets, const FigureOptions& opt,
                             const std::string& image_path);

}  // namespace chaosweep
