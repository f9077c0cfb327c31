#include "analysis/tune_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "analysis/grouping.hpp"
#include "analysis/tables.hpp"
#include "engine/tune/race_stats.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

std::vector<double> costs(const ResultSet& rs, const std::vector<std::size_t>& rows) {
  const auto& status = rs.text("status");
  const auto& ct = rs.num("coverage_time");
  std::vector<double> v;
  for (std::size_t r : rows) v.push_back(status[r] == "ok" ? ct[r] : inf);
  return v;
}

// The run parameters that take more than one value over `rows` (the seed
// aside: every configuration runs many).
std::vector<std::string> varying(const ResultSet& rs, const std::vector<std::size_t>& rows) {
  std::vector<std::string> out;
  for (const ParamInfo& p : param_table()) {
    const std::string name(p.name);
    if (name == "seed" || !rs.has(name) || rows.empty()) continue;
    bool differs = false;
    for (std::size_t r : rows) differs = differs || rs.cell(name, r) != rs.cell(name, rows[0]);
    if (differs) out.push_back(name);
  }
  return out;
}

std::string configuration(const ResultSet& rs, const std::vector<std::string>& params, std::size_t row) {
  std::string s;
  for (const std::string& p : params) s += (s.empty() ? "" : ", ") + p + " " + rs.cell(p, row);
  return s.empty() ? "(its own)" : s;
}

struct Validated {
  std::size_t runs = 0, ok = 0;
  double median = std::numeric_limits<double>::quiet_NaN();
  Interval interval{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
};

Validated validated(const ResultSet& rs, const std::vector<std::size_t>& rows, const TuneTableOptions& opt) {
  Validated v;
  const std::vector<double> c = costs(rs, rows);
  v.runs = c.size();
  for (double x : c) v.ok += std::isfinite(x);
  if (c.empty()) return v;
  v.median = median(c);
  v.interval = bootstrap_median_interval(c, opt.level, opt.resamples, 0);
  return v;
}

std::string interval_text(const Interval& i) {
  if (std::isnan(i.lo)) return "-";
  const auto f = [](double x) { return std::isinf(x) ? std::string("inf") : fmt_sig(x, 5); };
  return f(i.lo) + " - " + f(i.hi);
}

Cell ct_cell(double v) { return std::isinf(v) ? Cell("inf (missed)") : sig_cell(v, 5); }

// The tuner's choice against the grid's best on the validation seeds they
// share (both run on the same ones): the p-value of the paired Wilcoxon
// signed-rank test, as the race's own test pairs on the seed; NaN when the
// two did not run on the same seeds. Where the two medians are near equal,
// "at or below" alone is a coin toss; this says whether a difference is
// more than the seeds' noise.
double paired_p(const ResultSet& rs, const std::vector<std::size_t>& mine, const std::vector<std::size_t>& other) {
  constexpr double none = std::numeric_limits<double>::quiet_NaN();
  if (mine.empty() || mine.size() != other.size() || !rs.has("seed")) return none;
  const auto& seed = rs.num("seed");
  std::map<double, std::size_t> at;
  for (std::size_t r : other) at[seed[r]] = r;
  std::vector<std::size_t> paired;
  for (std::size_t r : mine) {
    const auto it = at.find(seed[r]);
    if (it == at.end()) return none;
    paired.push_back(it->second);
  }
  return wilcoxon_signed_rank_p(costs(rs, mine), costs(rs, paired));
}

}  // namespace

std::vector<std::string> tune_table_columns() {
  std::vector<std::string> c = {"run_id", "label", "race_round", "config_id", "status", "coverage_time"};
  for (const ParamInfo& p : param_table()) c.emplace_back(p.name);
  return c;
}

GridBest grid_best(const ResultSet& grid, const std::string& label, const std::vector<std::string>& params) {
  const auto& labels = grid.text("label");
  std::vector<std::size_t> rows;
  for (std::size_t r = 0; r < grid.rows(); ++r)
    if (labels[r] == label) rows.push_back(r);
  if (rows.empty()) throw AnalysisError("the grid's results have no run labelled '" + label + "'");
  for (const std::string& p : params)
    if (!grid.has(p)) throw AnalysisError("the grid's results have no column '" + p + "'");
  GridBest best;
  best.runs = rows.size();
  best.score = inf;
  bool found = false;
  for (const Group& g : group_rows(grid, params, rows)) {
    const double s = tuple_score(grid, g.rows);
    if (found && !(s < best.score)) continue;  // equal scores: the first tuple in key order
    found = true;
    best.score = s;
    best.values = g.key;
    best.numbers = g.key_num;
  }
  return best;
}

TextTable tune_table(const ResultSet& rs, const ResultSet* grid, const TuneTableOptions& opt) {
  for (const char* c : {"run_id", "race_round", "config_id", "label"})
    if (!rs.has(c))
      throw AnalysisError("table tune: the results have no '" + std::string(c) +
                          "' column: not a file of chaosweep tune");
  const auto& round = rs.num("race_round");
  const auto& config = rs.num("config_id");
  const auto& labels = rs.text("label");
  const auto& run_id = rs.num("run_id");
  // Cases in the order a whole tune first ran them, whatever order shards
  // were merged in: the raced ones (all in its first step), then those only
  // validated, each in the spec's order (a case's least run_id is its index:
  // a tune's run_ids are case + cases * k).
  std::vector<std::string> cases;
  std::map<std::string, double> least_id;
  std::map<std::string, std::vector<std::size_t>> race, chosen, beside;
  for (std::size_t r = 0; r < rs.rows(); ++r) {
    if (round[r] < 0) throw AnalysisError("table tune: row " + std::to_string(r) + " is a sweep's, not a tune's");
    const std::string& l = labels[r];
    if (!least_id.count(l)) {
      cases.push_back(l);
      least_id[l] = run_id[r];
    }
    least_id[l] = std::min(least_id[l], run_id[r]);
    if (round[r] > 0) race[l].push_back(r);
    else if (config[r] > 0) chosen[l].push_back(r);
    else beside[l].push_back(r);
  }
  std::stable_sort(cases.begin(), cases.end(), [&](const std::string& a, const std::string& b) {
    return std::pair(!race.count(a), least_id[a]) < std::pair(!race.count(b), least_id[b]);
  });
  TextTable t;
  t.title = "Tuned by racing: per case the configuration chosen, validated on fresh seeds";
  t.header = {"case", "configuration", "race runs", "configurations", "validated CT (median)", "interval", "ok"};
  const bool has_beside = !beside.empty();
  if (has_beside)
    t.header.insert(t.header.end(), {"grid's best, validated", "interval", "tuner <= grid", "paired test"});
  if (grid) t.header.insert(t.header.end(), {"grid's best", "its CT (grid seeds)", "grid runs"});
  std::size_t at_or_below = 0, compared = 0, race_runs = 0, grid_runs = 0;
  std::size_t tuner_better = 0, grid_better = 0, no_difference = 0;
  for (const std::string& l : cases) {
    const std::vector<std::size_t>& rows = race[l];
    race_runs += rows.size();
    std::set<double> ids;
    for (std::size_t r : rows) ids.insert(config[r]);
    const std::vector<std::string> params = opt.params.empty() ? varying(rs, rows) : opt.params;
    const std::vector<std::size_t>& v = chosen[l];
    const Validated mine = validated(rs, v, opt);
    std::vector<Cell> row = {Cell(l),
                             Cell(v.empty() ? "-" : configuration(rs, params, v[0])),
                             Cell(std::to_string(rows.size())),
                             Cell(std::to_string(ids.size())),
                             v.empty() ? Cell("-") : ct_cell(mine.median),
                             Cell(interval_text(mine.interval)),
                             Cell(std::to_string(mine.ok) + "/" + std::to_string(mine.runs))};
    if (has_beside) {
      const std::vector<std::size_t>& g = beside[l];
      const Validated other = validated(rs, g, opt);
      std::string verdict = "-";
      if (!g.empty() && !v.empty()) {
        ++compared;
        const bool ok = mine.median <= other.median;
        at_or_below += ok;
        verdict = ok ? "yes" : "no";
      }
      row.push_back(g.empty() ? Cell("-") : ct_cell(other.median));
      row.push_back(Cell(interval_text(other.interval)));
      row.push_back(Cell(verdict));
      const double p = paired_p(rs, v, g);
      std::string paired = "-";
      if (!std::isnan(p)) {
        const bool differ = p < 1 - opt.level, mine_lower = mine.median <= other.median;
        if (!differ) ++no_difference;
        else if (mine_lower) ++tuner_better;
        else ++grid_better;
        paired = std::string(!differ      ? "no difference"
                             : mine_lower ? "tuner better"
                                          : "grid better") +
                 " (p " + fmt_sig(p, 3) + ")";
      }
      row.push_back(Cell(paired));
    }
    if (grid) {
      const GridBest b = grid_best(*grid, l, params);
      grid_runs += b.runs;
      std::string text;
      for (std::size_t k = 0; k < params.size(); ++k) text += (k ? ", " : "") + params[k] + " " + b.values[k];
      row.push_back(Cell(text.empty() ? "(its own)" : text));
      row.push_back(ct_cell(b.score));
      row.push_back(Cell(std::to_string(b.runs)));
    }
    t.add_row(std::move(row));
  }
  t.notes.push_back(
      "validated CT: the median coverage time (s) of the configuration on seeds no race used, a run "
      "that missed the target counting as infinitely long; interval: percentile bootstrap of that "
      "median at " +
      fmt_sig(100 * opt.level, 3) + "% (" + std::to_string(opt.resamples) + " resamples)");
  if (has_beside) {
    t.notes.push_back("tuner at or below the grid's validated best in " + std::to_string(at_or_below) + " of " +
                      std::to_string(compared) + " cases");
    t.notes.push_back("paired test: Wilcoxon signed-rank of the two on the validation seeds they share, at " +
                      fmt_sig(100 * opt.level, 3) + "%: tuner better in " + std::to_string(tuner_better) +
                      ", grid better in " + std::to_string(grid_better) + ", no difference in " +
                      std::to_string(no_difference) + " of " +
                      std::to_string(tuner_better + grid_better + no_difference) + " cases");
  }
  std::string spent = "race runs: " + std::to_string(race_runs);
  if (grid && grid_runs > 0)
    spent += " (" + fmt_sig(100.0 * double(race_runs) / double(grid_runs), 3) + "% of the grid's " +
             std::to_string(grid_runs) + " runs of these cases)";
  t.notes.push_back(spent);
  return t;
}

}  // namespace chaosweep
