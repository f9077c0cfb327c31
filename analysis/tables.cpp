#include "analysis/tables.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "analysis/grouping.hpp"
#include "analysis/leaderboard.hpp"
#include "analysis/named_list.hpp"
#include "analysis/papers/bouncing_paper.hpp"
#include "analysis/papers/chebyshev_paper.hpp"
#include "analysis/papers/contraction_paper.hpp"
#include "analysis/papers/table1_readings.hpp"
#include "analysis/tune_table.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Columns that distinguish samples of one tuple, never parameters.
const std::set<std::string>& replicate_columns() {
  static const std::set<std::string> s{"seed"};
  return s;
}

// Parameter columns (the parameter table's names, and env) that take more
// than one value over `rows`, in parameter-table order.
std::vector<std::string> varying_params(const ResultSet& rs, const std::vector<std::size_t>& rows,
                                        const std::vector<std::string>& exclude) {
  std::vector<std::string> cands{"env"};
  for (const ParamInfo& p : param_table()) cands.emplace_back(p.name);
  std::vector<std::string> out;
  for (const std::string& c : cands) {
    if (!rs.has(c) || replicate_columns().count(c) || std::find(exclude.begin(), exclude.end(), c) != exclude.end())
      continue;
    std::set<std::string> seen;
    for (std::size_t r : rows) {
      seen.insert(rs.cell(c, r));
      if (seen.size() > 1) break;
    }
    if (seen.size() > 1) out.push_back(c);
  }
  return out;
}

std::string ok_count(const ResultSet& rs, const std::vector<std::size_t>& rows) {
  return std::to_string(ok_rows(rs, rows).size()) + "/" + std::to_string(rows.size());
}

// ------------------------------------------------------------------ best

struct RankedTuple {
  Group tuple;
  double score;
};

// The tuples of `params` over `rows` by score, all counted (`tuples`) but
// only the best `keep` returned: a sweep of a tuple per run has as many
// tuples as rows, and their keys' text is made for those kept only.
std::vector<RankedTuple> rank_tuples(const ResultSet& rs, const std::vector<std::string>& params,
                                     const std::vector<std::size_t>& rows, std::size_t keep,
                                     std::size_t* tuples = nullptr) {
  const RowSpans spans = group_spans(rs, params, rows);
  std::vector<double> score(spans.groups());
  std::vector<std::size_t> by_score(spans.groups());
  for (std::size_t g = 0; g < spans.groups(); ++g) {
    score[g] = tuple_score(rs, spans.rows_of(g, rows));
    by_score[g] = g;
  }
  if (tuples) *tuples = spans.groups();
  // Stable: equal scores keep the tuples' key order.
  std::stable_sort(by_score.begin(), by_score.end(), [&](std::size_t a, std::size_t b) { return score[a] < score[b]; });
  std::vector<RankedTuple> out;
  for (std::size_t k = 0; k < by_score.size() && k < keep; ++k) {
    Group t;
    t.rows = spans.rows_of(by_score[k], rows);
    for (const std::string& p : params) {
      t.key.push_back(rs.cell(p, t.rows[0]));
      t.key_num.push_back(rs.is_numeric(p) ? rs.num(p)[t.rows[0]] : nan);
    }
    out.push_back({std::move(t), score[by_score[k]]});
  }
  return out;
}

TextTable best_table(const ResultSet& rs, const TableOptions& opt) {
  if (opt.top < 1) throw AnalysisError("--top must be at least 1");
  TextTable t;
  t.title = "Best parameter tuples by median coverage time";
  const auto groups = group_rows(rs, opt.by, all_rows(rs));
  // One parameter list for the whole table, so that its columns line up.
  const std::vector<std::string> params = opt.params.empty() ? varying_params(rs, all_rows(rs), opt.by) : opt.params;
  for (const std::string& p : params)
    if (!rs.has(p)) (void)rs.num(p);  // names the missing column
  t.header = opt.by;
  t.header.push_back("rank");
  t.header.insert(t.header.end(), params.begin(), params.end());
  for (const char* h : {"median CT", "min CT", "ok", "median PR"}) t.header.emplace_back(h);
  for (const Group& g : groups) {
    const auto ranked = rank_tuples(rs, params, g.rows, std::size_t(opt.top));
    for (std::size_t k = 0; k < ranked.size() && int(k) < opt.top; ++k) {
      const RankedTuple& rt = ranked[k];
      std::vector<Cell> row(g.key.begin(), g.key.end());
      row.push_back(std::to_string(k + 1));
      row.insert(row.end(), rt.tuple.key.begin(), rt.tuple.key.end());
      row.push_back(std::isinf(rt.score) ? "-" : sig_cell(rt.score, 5));
      row.push_back(sig_cell(group_statistic(rs, rt.tuple.rows, "min"), 5));
      row.push_back(ok_count(rs, rt.tuple.rows));
      row.push_back(sig_cell(group_statistic(rs, rt.tuple.rows, "median", "pr"), 3));
      t.add_row(std::move(row));
    }
  }
  t.notes.push_back(
      "Tuples ranked by median CT over their runs, a run that did not reach the target counting as "
      "infinite; ties keep parameter order. PR = CT / T_opt.");
  return t;
}

// --------------------------------------------------------------- summary

TextTable summary_table(const ResultSet& rs, const TableOptions& opt) {
  std::vector<std::string> by = opt.by;
  if (by.empty() && rs.has("variant")) by = {"variant"};
  TextTable t;
  t.title = "Runs per group";
  t.header = by;
  for (const char* h :
       {"runs", "ok", "ok rate", "CT min", "CT q1", "CT median", "CT q3", "CT max", "median PR", "median coverage"})
    t.header.emplace_back(h);
  for (const Group& g : group_rows(rs, by, all_rows(rs))) {
    std::vector<Cell> row(g.key.begin(), g.key.end());
    row.push_back(std::to_string(g.rows.size()));
    row.push_back(std::to_string(ok_rows(rs, g.rows).size()));
    row.push_back(fixed_cell(group_statistic(rs, g.rows, "ok_rate"), 3));
    for (const char* s : {"min", "q1", "median", "q3", "max"})
      row.push_back(sig_cell(group_statistic(rs, g.rows, s), 5));
    row.push_back(sig_cell(group_statistic(rs, g.rows, "median", "pr"), 3));
    std::vector<double> cov;
    if (rs.has("final_coverage"))
      for (std::size_t r : g.rows) cov.push_back(rs.num("final_coverage")[r]);
    row.push_back(fixed_cell(quantile(cov, 0.5), 3));
    t.add_row(std::move(row));
  }
  t.notes.push_back(
      "CT quantiles over ok runs (linear interpolation, numpy's default); PR = CT / T_opt; "
      "median coverage: final coverage over all runs (the coverage reached when a run stopped).");
  return t;
}

// ---------------------------------------------------------------- table1

}  // namespace

std::map<std::string, std::pair<double, double>> read_paper(const std::string& path) {
  std::map<std::string, std::pair<double, double>> out;
  if (path.empty()) return out;
  std::ifstream in(path);
  if (!in) throw AnalysisError("--paper: cannot read " + path);
  std::string line;
  bool header = true;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      if (line.rfind("row,paper_ct", 0) != 0)
        throw AnalysisError("--paper: " + path + " must start with the header row,paper_ct,paper_pr");
      continue;
    }
    const auto cells = split_list(line);
    if (cells.size() < 2)
      throw AnalysisError("--paper: " + path + ":" + std::to_string(n) + ": expected row,paper_ct[,paper_pr]");
    try {
      out[cells[0]] = {std::stod(cells[1]), cells.size() > 2 ? std::stod(cells[2]) : nan};
    } catch (const std::exception&) {
      throw AnalysisError("--paper: " + path + ":" + std::to_string(n) + ": not a number");
    }
  }
  return out;
}

namespace {
bool flag(const ResultSet& rs, const char* col, const std::vector<std::size_t>& rows) {
  if (!rs.has(col)) return false;
  for (std::size_t r : rows)
    if (rs.num(col)[r] != 0) return true;
  return false;
}
}  // namespace

// The technique set of a case: what its runs switch on. Scaling is on when
// any run of the case has f != 1 (a search over f includes f = 1).
std::string technique(const ResultSet& rs, const std::vector<std::size_t>& rows) {
  if (rs.has("planner") && rs.text("planner")[rows[0]] == "logistic") return "Logistic map";
  std::string s;
  auto add = [&](const char* p) { s += (s.empty() ? "" : "+") + std::string(p); };
  if (flag(rs, "index_switching", rows)) add("IS");
  if (flag(rs, "map_zoning", rows)) add("MZ");
  bool scaled = false;
  for (std::size_t r : rows) scaled = scaled || rs.num("f")[r] != 1.0;
  if (scaled) add("SC");
  return s.empty() ? "original" : s;
}

double label_number(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return end && *end == '\0' && !s.empty() ? v : nan;
}

namespace {

// A Table 1 case: its runs, technique, best tuple and how many tuples it searched.
struct Table1Case {
  Group g;
  std::string technique;
  RankedTuple best;
  std::size_t tuples;
};

// Cases: the spec's label (a Table 1 row) when every run has one.
std::vector<Table1Case> table1_cases(const ResultSet& rs, bool labelled) {
  const std::vector<std::string> case_keys =
      labelled ? std::vector<std::string>{"label"} : std::vector<std::string>{"size_x", "sr", "env", "variant"};
  std::vector<Table1Case> cases;
  const std::vector<std::string> tuple_keys{"c", "ds_index", "f"};
  for (Group& g : group_rows(rs, case_keys, all_rows(rs))) {
    std::size_t tuples = 0;
    auto ranked = rank_tuples(rs, tuple_keys, g.rows, 1, &tuples);
    const std::string tech = technique(rs, g.rows);
    cases.push_back({std::move(g), tech, std::move(ranked.front()), tuples});
  }
  // Table 1's row order: by row number when the labels are numbers.
  std::stable_sort(cases.begin(), cases.end(), [](const Table1Case& a, const Table1Case& b) {
    const double x = label_number(a.g.key[0]), y = label_number(b.g.key[0]);
    if (std::isnan(x) || std::isnan(y)) return false;
    return x < y;
  });
  return cases;
}

// A case's map (size, SR, env), the key of the original Arnold's best CT.
std::string map_of(const ResultSet& rs, const Table1Case& c) {
  const std::size_t r = c.g.rows[0];
  return rs.cell("size_x", r) + "|" + rs.cell("sr", r) + "|" + rs.text("env")[r];
}

std::vector<Cell> table1_row(const ResultSet& rs, const Table1Case& c, const std::string& row_name, double base,
                             const std::map<std::string, std::pair<double, double>>& paper) {
  const std::size_t r = c.best.tuple.rows[0];
  const bool mz = c.technique.find("MZ") != std::string::npos;
  const bool sc = c.technique.find("SC") != std::string::npos;
  const bool logistic = c.technique == "Logistic map";
  const double ct = c.best.score;
  const double gain = (base - ct) / base * 100.0, hours = (base - ct) / 3600.0;
  std::vector<Cell> row{row_name,
                        c.technique,
                        rs.cell("size_x", r) + " m",
                        rs.cell("sr", r),
                        rs.text("env")[r],
                        mz ? rs.cell("c", r) : "N/A",
                        logistic ? "N/A" : rs.cell("ds_index", r),
                        sc ? rs.cell("f", r) : "N/A",
                        std::isinf(ct) ? "-" : sig_cell(ct, 5),
                        ok_count(rs, c.best.tuple.rows),
                        std::to_string(c.tuples),
                        std::isfinite(gain) ? fixed_cell(gain, 1) : "-",
                        std::isfinite(hours) ? fixed_cell(hours, 2) : "-",
                        std::isinf(ct) ? "-" : fixed_cell(ct / rs.num("t_opt")[r], 2)};
  if (!paper.empty()) {
    const auto p = paper.find(c.g.key[0]);
    row.push_back(p == paper.end() ? "-" : sig_cell(p->second.first, 5));
    row.push_back(p == paper.end() || std::isinf(ct) ? "-" : fixed_cell(ct / p->second.first, 2));
  }
  return row;
}

TextTable table1(const ResultSet& rs, const TableOptions& opt) {
  for (const char* c : {"size_x", "sr", "env", "c", "ds_index", "f", "coverage_time", "status", "t_opt"})
    if (!rs.has(c)) (void)rs.num(c);
  const auto paper = read_paper(opt.paper);
  const bool labelled = every_run_labelled(rs);
  const std::vector<Table1Case> cases = table1_cases(rs, labelled);
  // The original Arnold's best CT per map (size, SR, env).
  std::map<std::string, double> original;
  for (const Table1Case& c : cases)
    if (c.technique == "original") {
      auto [it, fresh] = original.try_emplace(map_of(rs, c), c.best.score);
      if (!fresh) it->second = std::min(it->second, c.best.score);
    }

  TextTable t;
  t.title = "Table 1: best parameters per case (median CT over each tuple's runs)";
  t.header = {"row",    "technique",     "map",           "SR", "env", "c", "DSindex", "f", "CT (s)", "ok",
              "tuples", "improvement %", "improvement h", "PR"};
  if (!paper.empty()) {
    t.header.emplace_back("paper CT (s)");
    t.header.emplace_back("CT / paper");
  }
  for (const Table1Case& c : cases) {
    const auto orig = original.find(map_of(rs, c));
    const double base = orig == original.end() || c.technique == "original" ? nan : orig->second;
    t.add_row(table1_row(rs, c, labelled ? c.g.key[0] : std::to_string(&c - cases.data() + 1), base, paper));
  }
  t.notes.push_back(
      "Per case, the parameter tuple (c, DSindex, f) with the lowest median CT over its runs "
      "(a run that missed the target counts as infinite); ok = its runs that reached the target; "
      "tuples = tuples searched.");
  t.notes.push_back(
      "Improvement over the best original Arnold tuple on the same map (size, SR, env); "
      "PR = CT / T_opt, T_opt = 0.9 free area / (SR v).");
  return t;
}

}  // namespace

bool every_run_labelled(const ResultSet& rs) {
  bool labelled = rs.has("label");
  if (labelled)
    for (const std::string& l : rs.text("label")) labelled = labelled && !l.empty();
  return labelled;
}

double tuple_score(const ResultSet& rs, const std::vector<std::size_t>& rows) {
  std::vector<double> v;
  const auto& status = rs.text("status");
  const auto& ct = rs.num("coverage_time");
  for (std::size_t r : rows) v.push_back(status[r] == "ok" ? ct[r] : inf);
  if (v.empty()) return inf;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  // Median; with infinities present the upper middle decides (never inf - inf).
  if (n % 2) return v[n / 2];
  if (std::isinf(v[n / 2])) return inf;
  return 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

struct TableKind {
  std::string name;
  bool needs_results;
  TextTable (*make)(const ResultSet&, const TableOptions&);
};

// Every table `chaosweep table` knows: its dispatch, its list of names and
// `--help`'s list are all this one list.
const std::vector<TableKind>& table_kinds() {
  static const std::vector<TableKind> kinds{
      {"table1", true, table1},
      {"best", true, best_table},
      {"summary", true, summary_table},
      {"leaderboard", true, [](const ResultSet& rs, const TableOptions& opt) { return leaderboard_table(rs, opt.by); }},
      {"seed001", false, [](const ResultSet&, const TableOptions&) { return seed001_table(); }},
      {"seed002", false,
       [](const ResultSet&, const TableOptions& opt) {
         BouncingPaperOptions o;
         o.bins = opt.bins;
         return seed002_table(o);
       }},
      {"seed003", true, [](const ResultSet& rs, const TableOptions&) { return seed003_table(rs); }},
      {"readings", true, table1_readings},
      {"tune", true,
       [](const ResultSet& rs, const TableOptions& opt) {
         TuneTableOptions o;
         o.params = opt.params;
         if (opt.grid.empty()) return tune_table(rs, nullptr, o);
         const ResultSet grid = ResultSet::load({opt.grid});
         return tune_table(rs, &grid, o);
       }},
  };
  return kinds;
}

const TableKind& table_kind(const std::string& name) { return find_named(table_kinds(), name, "table"); }

}  // namespace

const std::vector<std::string>& table_names() {
  static const std::vector<std::string> names = names_of(table_kinds());
  return names;
}

bool table_needs_results(const std::string& name) { return table_kind(name).needs_results; }

TableColumns table_columns(const std::string& name, const TableOptions& opt) {
  TableColumns t;
  if (name == "tune") {
    t.all = false;
    t.columns = tune_table_columns();
    return t;
  }
  if (name == "leaderboard") {
    t.all = false;
    t.columns = leaderboard_columns(opt.by);
    return t;
  }
  if (name != "summary" && name != "best") return t;
  t.all = false;
  t.columns = opt.by;
  if (name == "summary") {
    if (opt.by.empty()) t.columns.emplace_back("variant");
    t.columns.emplace_back("final_coverage");
  } else if (opt.params.empty()) {
    t.if_varying.emplace_back("env");  // varying_params' candidates
    for (const ParamInfo& p : param_table()) t.if_varying.emplace_back(p.name);
  } else {
    t.columns.insert(t.columns.end(), opt.params.begin(), opt.params.end());
  }
  for (const char* c : {"status", "coverage_time", "pr"}) t.columns.emplace_back(c);
  return t;
}

TextTable make_table(const std::string& name, const ResultSet& rs, const TableOptions& opt) {
  const TableKind& kind = table_kind(name);
  if (kind.needs_results && rs.rows() == 0) throw AnalysisError("the result files hold no runs");
  return kind.make(rs, opt);
}

}  // namespace chaosweep
