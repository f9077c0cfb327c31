#pragma once
// `chaosweep table leaderboard`: the planners of a benchmark's result files
// ranked on each map by median coverage time (a run short of the target
// counting as infinitely long), beside their path metrics, and their mean
// rank over the maps: one table for planners that no two papers measured
// alike.
#include <string>
#include <vector>

#include "analysis/result_set.hpp"
#include "analysis/text_table.hpp"

namespace chaosweep {

// `planner`: the columns that name a planner (empty: `label` when every run
// has one, else `variant`). A map is a value of (env, size_x, size_y, sr).
TextTable leaderboard_table(const ResultSet& rs, std::vector<std::string> planner);
// The columns the table reads (ResultSet::load's `columns`; those a file
// lacks, such as the path metrics of older files, show as "-").
std::vector<std::string> leaderboard_columns(const std::vector<std::string>& planner);

}  // namespace chaosweep
