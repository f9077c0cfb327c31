#include "analysis/leaderboard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "analysis/grouping.hpp"
#include "analysis/tables.hpp"

namespace chaosweep {

namespace {

const std::vector<std::string>& map_keys() {
  static const std::vector<std::string> k{"env", "size_x", "size_y", "sr"};
  return k;
}

// Median of a column over rows (finite values only); NaN when the files
// lack the column or no value is finite.
double column_median(const ResultSet& rs, const char* column, const std::vector<std::size_t>& rows) {
  if (!rs.has(column)) return std::numeric_limits<double>::quiet_NaN();
  const std::vector<double>& values = rs.num(column);
  std::vector<double> v;
  for (std::size_t r : rows)
    if (std::isfinite(values[r])) v.push_back(values[r]);
  return quantile(std::move(v), 0.5);
}

std::string map_name(const ResultSet& rs, std::size_t row) {
  std::string s = rs.cell("env", row) + " " + rs.cell("size_x", row);
  if (rs.cell("size_y", row) != rs.cell("size_x", row)) s += "x" + rs.cell("size_y", row);
  return s + " m, SR " + rs.cell("sr", row);
}

// Ranks 1..n of scores, ties sharing the mean of their places (so a mean
// rank over maps treats ties alike, as Friedman's test does).
std::vector<double> fractional_ranks(const std::vector<double>& score) {
  std::vector<std::size_t> order(score.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return score[a] < score[b]; });
  std::vector<double> rank(score.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && score[order[j + 1]] == score[order[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) rank[order[k]] = 0.5 * double(i + j) + 1.0;
    i = j + 1;
  }
  return rank;
}

}  // namespace

std::vector<std::string> leaderboard_columns(const std::vector<std::string>& planner) {
  std::vector<std::string> c = planner.empty() ? std::vector<std::string>{"label", "variant"} : planner;
  c.insert(c.end(), map_keys().begin(), map_keys().end());
  for (const char* k : {"coverage_time", "pr", "final_coverage", "visit_evenness", "turn_entropy", "coverage_area"})
    c.emplace_back(k);
  return c;
}

Leaderboard rank_planners(const ResultSet& rs, std::vector<std::string> planner) {
  if (planner.empty()) planner = {every_run_labelled(rs) ? "label" : "variant"};
  for (const std::string& k : map_keys()) (void)rs.cell(k, 0);  // names a missing map column
  Leaderboard lb;
  lb.planner = planner;
  std::map<std::string, std::size_t> overall;  // planner name -> index in lb.overall, as first met
  for (const Group& m : group_rows(rs, map_keys(), all_rows(rs))) {
    lb.maps.push_back(map_name(rs, m.rows[0]));
    const std::vector<Group> planners = group_rows(rs, planner, m.rows);
    std::vector<double> score;
    for (const Group& p : planners) score.push_back(tuple_score(rs, p.rows));
    const std::vector<double> rank = fractional_ranks(score);
    std::vector<std::size_t> by_rank(planners.size());
    for (std::size_t i = 0; i < by_rank.size(); ++i) by_rank[i] = i;
    std::stable_sort(by_rank.begin(), by_rank.end(), [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
    for (std::size_t i : by_rank) {
      const Group& p = planners[i];
      std::string name;
      for (const std::string& k : p.key) name += (name.empty() ? "" : " ") + k;
      if (!overall.count(name)) {
        overall[name] = lb.overall.size();
        lb.overall.push_back({name, 0.0, 0, 0, {}});
      }
      Leaderboard::Standing& st = lb.overall[overall[name]];
      st.mean_rank += rank[i];
      st.maps += 1;
      st.wins += rank[i] == 1.0;
      st.rows.insert(st.rows.end(), p.rows.begin(), p.rows.end());
      lb.entries.push_back({lb.maps.size() - 1, p.key, p.rows, score[i], rank[i]});
    }
  }
  // Overall: mean rank over the maps each planner ran on, then wins; ties
  // keep the order planners were first met in.
  for (Leaderboard::Standing& st : lb.overall) st.mean_rank /= st.maps;
  std::stable_sort(lb.overall.begin(), lb.overall.end(), [](const auto& x, const auto& y) {
    return x.mean_rank != y.mean_rank ? x.mean_rank < y.mean_rank : x.wins > y.wins;
  });
  return lb;
}

TextTable leaderboard_table(const ResultSet& rs, std::vector<std::string> planner) {
  const Leaderboard lb = rank_planners(rs, std::move(planner));
  TextTable t;
  t.title = "Leaderboard: planners ranked on each map by median coverage time";
  t.header = {"map", "rank"};
  t.header.insert(t.header.end(), lb.planner.begin(), lb.planner.end());
  for (const char* h : {"runs", "ok rate", "median CT", "median PR", "median coverage", "visit evenness",
                        "turn entropy", "coverage area"})
    t.header.emplace_back(h);
  for (const Leaderboard::Entry& e : lb.entries) {
    std::vector<Cell> row{lb.maps[e.map], sig_cell(e.rank, 3)};
    row.insert(row.end(), e.key.begin(), e.key.end());
    row.push_back(std::to_string(e.rows.size()));
    row.push_back(fixed_cell(group_statistic(rs, e.rows, "ok_rate"), 3));
    row.push_back(std::isinf(e.score) ? "-" : sig_cell(e.score, 5));
    row.push_back(sig_cell(group_statistic(rs, e.rows, "median", "pr"), 3));
    for (const char* c : {"final_coverage", "visit_evenness", "turn_entropy", "coverage_area"}) {
      const double v = column_median(rs, c, e.rows);
      row.push_back(std::isnan(v) ? Cell("-") : fixed_cell(v, 3));
    }
    t.add_row(std::move(row));
  }
  std::string overall = "Overall, mean rank over the " + std::to_string(lb.maps.size()) + " map(s) (wins):";
  for (std::size_t i = 0; i < lb.overall.size(); ++i) {
    const Leaderboard::Standing& s = lb.overall[i];
    overall += (i ? "; " : " ") + s.name + " " + sig_cell(s.mean_rank, 3).shown + " (" + std::to_string(s.wins) + ")";
    if (std::size_t(s.maps) < lb.maps.size()) overall += " on " + std::to_string(s.maps) + " map(s)";
  }
  t.notes.push_back(overall + ".");
  t.notes.push_back(
      "Rank by median CT over a planner's runs on the map, a run that did not reach the target counting as "
      "infinite; ties share the mean of their places. PR = CT / T_opt; coverage, visit evenness (Pielou's J of "
      "cell entries over the free cells), turn entropy (bits) and coverage area (the mean time at which the cells "
      "the target needs were first visited, over T_opt: 0.5 for a steady lawnmower; lower is faster) are medians "
      "over all runs (docs/spec.md 1); - : the files lack the column.");
  return t;
}

}  // namespace chaosweep
