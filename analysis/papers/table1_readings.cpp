#include "analysis/papers/table1_readings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "analysis/grouping.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/math/splitmix.hpp"

namespace chaosweep {

namespace {

constexpr double no_reading = std::numeric_limits<double>::quiet_NaN();

struct Case {
  std::vector<std::string> reading;  // the reading columns' values
  std::string label, env, signature;
  bool obstacles = false, map_zoning = false;
  std::string technique;
  std::vector<std::size_t> rows;
  double median = no_reading;  // timeouts count as infinite (tuple_score)
};

// The 5% and 95% points of median(a) / median(b) over bootstrap resamples of
// both (timeouts infinite, as tuple_score), from a fixed seed: the sampling
// uncertainty of a ratio of two 32-run medians.
std::pair<double, double> bootstrap_ratio(const ResultSet& rs, const std::vector<std::size_t>& a,
                                          const std::vector<std::size_t>& b) {
  constexpr int resamples = 2000;
  std::uint64_t state = 21;
  auto resample = [&](const std::vector<std::size_t>& rows) {
    std::vector<std::size_t> out(rows.size());
    for (std::size_t& r : out) r = rows[std::size_t(uniform01(state) * double(rows.size()))];
    return tuple_score(rs, out);
  };
  std::vector<double> ratios;
  for (int i = 0; i < resamples; ++i) {
    const double x = resample(a), y = resample(b);
    ratios.push_back(std::isinf(x) ? std::numeric_limits<double>::infinity() : x / y);
  }
  std::sort(ratios.begin(), ratios.end());
  return {ratios[std::size_t(0.05 * (resamples - 1))], ratios[std::size_t(0.95 * (resamples - 1))]};
}

// A map has obstacles when it has fewer free cells than cells.
bool has_obstacles(const ResultSet& rs, std::size_t r) {
  const double cells =
      std::ceil(rs.num("size_x")[r] / rs.num("sr")[r]) * std::ceil(rs.num("size_y")[r] / rs.num("sr")[r]);
  return rs.num("free_cells")[r] < cells;
}

}  // namespace

const std::vector<std::string>& reading_columns() {
  static const std::vector<std::string> c{"obstacle_response", "transit_time",   "transit_replan", "zone_goal",
                                          "zone_order",        "logistic_reset", "coverage_cells", "boundary"};
  return c;
}

namespace {

// The reading columns whose values differ between runs.
std::vector<std::string> differing_readings(const ResultSet& rs) {
  std::vector<std::string> keys;
  for (const std::string& c : reading_columns()) {
    if (!rs.has(c)) continue;
    std::set<std::string> seen;
    for (std::size_t r = 0; r < rs.rows() && seen.size() < 2; ++r) seen.insert(rs.cell(c, r));
    if (seen.size() > 1) keys.push_back(c);
  }
  return keys;
}

// "transit_time=distance, coverage_cells=all"; "defaults" when none differs.
std::string reading_name(const std::vector<std::string>& keys, const std::vector<std::string>& values) {
  std::string out;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const ParamInfo* info = find_param(keys[i]);
    const bool is_default = info && info->kind == ParamInfo::Kind::choice &&
                            values[i] == info->choices[std::size_t(info->get(RunParams{}))];
    if (!is_default) out += (out.empty() ? "" : ", ") + keys[i] + "=" + values[i];
  }
  return out.empty() ? std::string("defaults") : out;
}

// The cases (reading, label, env), in the order the runs first meet the
// readings (a spec's parts), rows by number.
std::vector<Case> reading_cases(const ResultSet& rs, const std::vector<std::string>& keys) {
  std::vector<std::string> case_keys = keys;
  for (const char* c : {"label", "env"}) case_keys.emplace_back(c);
  std::vector<Case> cases;
  for (const Group& g : group_rows(rs, case_keys, all_rows(rs))) {
    Case k;
    k.reading.assign(g.key.begin(), g.key.end() - 2);
    k.label = g.key[keys.size()];
    k.env = g.key[keys.size() + 1];
    k.rows = g.rows;
    const std::size_t r = g.rows[0];
    k.obstacles = has_obstacles(rs, r);
    k.map_zoning = rs.num("map_zoning")[r] != 0;
    k.technique = technique(rs, g.rows);
    // What an obstacle row shares with its open-map row (Table 1: same size, SR, techniques and parameters).
    // (DSindex aside: the paper's rows 4 and 1 pick different ones.)
    k.signature = rs.cell("size_x", r) + "|" + rs.cell("sr", r) + "|" + k.technique + "|" +
                  (k.map_zoning ? rs.cell("c", r) : "") + "|" + rs.cell("f", r);
    k.median = tuple_score(rs, g.rows);
    cases.push_back(std::move(k));
  }
  std::map<std::vector<std::string>, double> first;
  for (const Case& k : cases) {
    double id = rs.has("run_id") ? rs.num("run_id")[k.rows[0]] : 0;
    for (std::size_t r : k.rows) id = std::min(id, rs.has("run_id") ? rs.num("run_id")[r] : 0);
    auto [it, fresh] = first.try_emplace(k.reading, id);
    if (!fresh) it->second = std::min(it->second, id);
  }
  std::stable_sort(cases.begin(), cases.end(), [&](const Case& a, const Case& b) {
    if (a.reading != b.reading) return first[a.reading] < first[b.reading];
    const double x = label_number(a.label), y = label_number(b.label);
    return std::isnan(x) || std::isnan(y) ? a.label < b.label : x < y;
  });
  return cases;
}

// The open-map row of an obstacle row: the same reading's, else (without
// map zoning, which is all that a reading can change on an open map) any.
const Case* open_partner(const std::vector<Case>& cases, const Case& k) {
  const Case* any = nullptr;
  for (const Case& o : cases) {
    if (o.obstacles || o.signature != k.signature) continue;
    if (o.reading == k.reading) return &o;
    if (!any && !k.map_zoning) any = &o;
  }
  return any;
}

using PaperCts = std::map<std::string, std::pair<double, double>>;

double paper_ct(const PaperCts& paper, const std::string& label) {
  const auto p = paper.find(label);
  return p == paper.end() ? no_reading : p->second.first;
}

// The columns after the reading: the row's CTs, the paper's, and the ratio
// to the open-map row `o` (none when null).
void add_ct_cells(std::vector<Cell>& row, const ResultSet& rs, const Case& k, const Case* o, const PaperCts& paper) {
  const auto ok = ok_rows(rs, k.rows);
  const double lo = group_statistic(rs, k.rows, "min"), hi = group_statistic(rs, k.rows, "max");
  const double pct = paper_ct(paper, k.label);
  const bool timeouts = ok.size() < k.rows.size();
  std::string inside = "-";
  if (!std::isnan(pct) && !ok.empty()) inside = pct >= lo && (pct <= hi || timeouts) ? "yes" : "no";
  for (Cell c : {Cell(k.env), Cell(k.label), Cell(k.technique),
                 Cell(std::to_string(ok.size()) + "/" + std::to_string(k.rows.size())),
                 std::isinf(k.median) ? Cell("-") : sig_cell(k.median, 5), sig_cell(lo, 5), sig_cell(hi, 5),
                 sig_cell(pct, 5), Cell(inside)})
    row.push_back(std::move(c));
  if (!o) {
    for (int i = 0; i < 5; ++i) row.push_back("-");
    return;
  }
  const double ours = k.median / o->median, theirs = pct / paper_ct(paper, o->label);
  row.push_back(o->label);
  row.push_back(fixed_cell(ours, 2));
  row.push_back(fixed_cell(theirs, 2));
  row.push_back(fixed_cell(ours / theirs, 2));
  const auto [lo_r, hi_r] = bootstrap_ratio(rs, k.rows, o->rows);
  row.push_back(std::isfinite(lo_r) && std::isfinite(hi_r)
                    ? "[" + fmt_fixed(lo_r / theirs, 2) + ", " + fmt_fixed(hi_r / theirs, 2) + "]"
                    : "-");
}

}  // namespace

TextTable table1_readings(const ResultSet& rs, const TableOptions& opt) {
  for (const char* c : {"label", "env", "size_x", "size_y", "sr", "free_cells", "ds_index", "c", "f", "map_zoning",
                        "status", "coverage_time"})
    if (!rs.has(c)) (void)rs.num(c);
  const bool named = opt.by.empty();  // one "reading" column naming what differs from the defaults
  const std::vector<std::string> keys = named ? differing_readings(rs) : opt.by;
  const auto paper = read_paper(opt.paper);
  const std::vector<Case> cases = reading_cases(rs, keys);

  TextTable t;
  t.title = "Table 1 rows under readings of the paper (CT over each row's runs)";
  t.header = named ? std::vector<std::string>{"reading"} : keys;
  for (const char* h :
       {"env", "row", "technique", "ok", "median CT", "min CT", "max CT", "paper CT", "paper in [min, max]", "open row",
        "CT / open", "paper CT / open", "ratio / paper's", "ratio / paper's, 90% interval"})
    t.header.emplace_back(h);
  for (const Case& k : cases) {
    std::vector<Cell> row;
    if (named) row.emplace_back(reading_name(keys, k.reading));
    else row.assign(k.reading.begin(), k.reading.end());
    add_ct_cells(row, rs, k, k.obstacles ? open_partner(cases, k) : nullptr, paper);
    t.add_row(std::move(row));
  }
  t.notes.push_back(
      "Per reading (the columns before env) and row: median CT over the row's runs (a run that "
      "missed the target counts as infinite), min and max over those that reached it; paper in "
      "[min, max]: the paper's CT lies within our runs' range (above our min, and below our max or "
      "some run timed out).");
  t.notes.push_back(
      "CT / open: an obstacle row's median over the median of the open-map row with the same size, "
      "SR, techniques and parameters, DSindex aside (the same reading's, else any: on an open map a "
      "reading changes only map zoning); paper CT / open: the same ratio of the paper's CTs; the "
      "interval: 5% and 95% of the ratio over 2000 bootstrap resamples of both rows' runs.");
  return t;
}

}  // namespace chaosweep
