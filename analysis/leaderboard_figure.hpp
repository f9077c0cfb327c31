#pragma once
// `chaosweep figure leaderboard`: the leaderboard as a performance profile.
#include <string>

#include "analysis/figures.hpp"
#include "analysis/result_set.hpp"

namespace chaosweep {

// Per planner (--by, as `table leaderboard`), in the leaderboard's overall
// order: the share of its runs over every map that reached the target
// within a PR (CT / T_opt, so maps of any size compare), against PR on a
// log axis. A curve that stays low never reached the target in the rest of
// its runs; one further left covers in less of the lawnmower's time.
FigureOutput leaderboard_figure(const ResultSet& rs, const FigureOptions& opt, const std::string& path);

}  // namespace chaosweep
