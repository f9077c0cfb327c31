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

// The ranking the table and `figure leaderboard` show.
struct Leaderboard {
  struct Entry {                   // one planner on one map
    std::size_t map;               // index in maps
    std::vector<std::string> key;  // the planner's values of the planner columns
    std::vector<std::size_t> rows;
    double score;  // median CT, a run short of the target counting as infinite
    double rank;   // 1.., ties sharing the mean of their places
  };
  struct Standing {    // one planner over the maps it ran on
    std::string name;  // its key, space-joined
    double mean_rank;
    int maps, wins;
    std::vector<std::size_t> rows;  // on every map
  };
  std::vector<std::string> planner;  // the columns naming a planner
  std::vector<std::string> maps;     // "env L m, SR s", in group order
  std::vector<Entry> entries;        // by map, then rank
  std::vector<Standing> overall;     // by mean rank, then wins
};
Leaderboard rank_planners(const ResultSet& rs, std::vector<std::string> planner);

// `planner`: the columns that name a planner (empty: `label` when every run
// has one, else `variant`). A map is a value of (env, size_x, size_y, sr).
TextTable leaderboard_table(const ResultSet& rs, std::vector<std::string> planner);
// The columns the table reads (ResultSet::load's `columns`; those a file
// lacks, such as the path metrics of older files, show as "-").
std::vector<std::string> leaderboard_columns(const std::vector<std::string>& planner);

}  // namespace chaosweep
