#include "analysis/papers/contraction_paper.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/grouping.hpp"

namespace chaosweep {

namespace {

// The paper's Table 1 (coverage %, n = 800, headings x, y, z) by start
// point (s, s); Table 2's mean and sample standard deviation; Table 3
// (coverage % vs n at (10, 10), heading z); Section 6 and Figs. 15-16.
constexpr double paper_t1[10][3] = {
    {56.76, 44.25, 41.25}, {66.25, 35.75, 58.50}, {27.75, 38.75, 40.75}, {38.25, 42.25, 35.25}, {34.75, 53.25, 56.00},
    {39.25, 46.00, 47.50}, {33.25, 40.00, 40.50}, {43.25, 46.50, 57.00}, {54.75, 22.00, 49.00}, {60.00, 28.75, 50.25}};
constexpr double paper_mean[3] = {45.426, 39.75, 47.60}, paper_sd[3] = {13.0405, 9.1074, 8.0062};
const std::map<int, double> paper_t3 = {{200, 46.25},   {300, 55.75},   {500, 52.50},   {800, 54.50},  {1200, 62.50},
                                        {1700, 59.75},  {2300, 54.75},  {3000, 49.75},  {3800, 54.00}, {4700, 55.50},
                                        {5700, 56.50},  {6800, 58.50},  {8000, 61.50},  {9300, 66.00}, {10700, 39.75},
                                        {12200, 16.25}, {13800, 10.00}, {15500, 10.00}, {17300, 9.75}, {19200, 9.75}};
const std::map<int, std::pair<int, double>> paper_mirror = {
    {418, {20, 12.0}}, {779, {100, 16.75}}, {3401, {500, 55.75}}, {7121, {1500, 62.5}}};

const char* heading_name(int ds) { return ds == 1 ? "x" : ds == 2 ? "y" : "z"; }

std::vector<std::size_t> part_rows(const ResultSet& rs, const std::string& part) {
  std::vector<std::size_t> out;
  for (std::size_t r = 0; r < rs.rows(); ++r)
    if (rs.text("label")[r] == part) out.push_back(r);
  return out;
}

double pct(const ResultSet& rs, std::size_t r) { return 100.0 * rs.num("final_coverage")[r]; }

// Tables 1 and 2.
void add_tables_1_2(TextTable& t, const ResultSet& rs) {
  std::vector<double> by_heading[3];
  for (std::size_t r : part_rows(rs, "table1")) {
    const int ds = int(rs.num("ds_index")[r]);
    const int s = int(std::lround(rs.num("start_x")[r]));
    by_heading[ds - 1].push_back(pct(rs, r));
    const bool known = s >= 0 && s <= 9 && rs.num("c3_n")[r] == 800;
    t.add_row({"Table 1", "(" + rs.cell("start_x", r) + ", " + rs.cell("start_y", r) + ")",
               std::string("coverage % at n = ") + rs.cell("c3_n", r) + ", heading " + heading_name(ds),
               fixed_cell(pct(rs, r), 2), known ? fixed_cell(paper_t1[s][ds - 1], 2) : "-"});
  }
  for (int h = 0; h < 3; ++h) {
    const auto& v = by_heading[h];
    if (v.empty()) continue;
    double mean = 0, ss = 0;
    for (double x : v) mean += x / double(v.size());
    for (double x : v) ss += (x - mean) * (x - mean);
    const double sd = v.size() > 1 ? std::sqrt(ss / double(v.size() - 1)) : 0.0;
    t.add_row({"Table 2", std::string("heading ") + heading_name(h + 1), "mean coverage %", fixed_cell(mean, 3),
               fixed_cell(paper_mean[h], 3)});
    t.add_row({"Table 2", std::string("heading ") + heading_name(h + 1), "standard deviation (n - 1)",
               fixed_cell(sd, 4), fixed_cell(paper_sd[h], 4)});
  }
}

// Table 3.
void add_table_3(TextTable& t, const ResultSet& rs) {
  for (std::size_t r : part_rows(rs, "table3")) {
    const int n = int(rs.num("c3_n")[r]);
    const auto p = paper_t3.find(n);
    t.add_row({"Table 3", "n = " + std::to_string(n), "coverage % from (10, 10), heading z", fixed_cell(pct(rs, r), 2),
               p == paper_t3.end() ? "-" : fixed_cell(p->second, 2)});
  }
}

// The chaotic spread (experiments/seed003_spread.toml): Table 2's mean and
// sd over ic-jittered samples per heading, and Table 3's coverage over
// samples per n, with the share that collapsed to the paper's ~10%.
void add_spread(TextTable& t, const ResultSet& rs) {
  for (const Group& g : group_rows(rs, {"ic_jitter", "ds_index"}, part_rows(rs, "table1-spread"))) {
    std::vector<double> v;
    for (std::size_t r : g.rows) v.push_back(pct(rs, r));
    const double mean = value_statistic(v, "mean");
    double ss = 0;
    for (double x : v) ss += (x - mean) * (x - mean);
    const int ds = int(std::lround(g.key_num[1]));
    const std::string row = "heading " + std::string(heading_name(ds)) + ", ic +-" + g.key[0] + ", " +
                            std::to_string(v.size()) + " samples";
    t.add_row({"Table 2 (spread)", row, "mean coverage %", fixed_cell(mean, 3), fixed_cell(paper_mean[ds - 1], 3)});
    t.add_row({"Table 2 (spread)", row, "standard deviation (n - 1)",
               fixed_cell(v.size() > 1 ? std::sqrt(ss / double(v.size() - 1)) : 0.0, 4),
               fixed_cell(paper_sd[ds - 1], 4)});
  }
  for (const Group& g : group_rows(rs, {"ic_jitter", "c3_n"}, part_rows(rs, "table3-spread"))) {
    std::vector<double> v;
    for (std::size_t r : g.rows) v.push_back(pct(rs, r));
    const int n = int(std::lround(g.key_num[1]));
    const auto p = paper_t3.find(n);
    const std::string row =
        "n = " + std::to_string(n) + ", ic +-" + g.key[0] + ", " + std::to_string(v.size()) + " samples";
    t.add_row({"Table 3 (spread)", row, "median coverage % [min, max]",
               fmt_fixed(value_statistic(v, "median"), 2) + " [" + fmt_fixed(value_statistic(v, "min"), 2) + ", " +
                   fmt_fixed(value_statistic(v, "max"), 2) + "]",
               p == paper_t3.end() ? "-" : fixed_cell(p->second, 2)});
    const double collapsed =
        double(std::count_if(v.begin(), v.end(), [](double x) { return x <= 12.0; })) / double(v.size());
    t.add_row({"Table 3 (spread)", row, "share of samples at <= 12% (collapsed)", fixed_cell(collapsed, 3), "-"});
  }
}

// Section 6: the complete-coverage loop.
void add_loop(TextTable& t, const ResultSet& rs) {
  for (std::size_t r : part_rows(rs, "loop")) {
    const std::string row = "ic grid step " + rs.cell("c3_ic_grid", r);
    t.add_row({"Section 6", row, "sections", rs.cell("segments", r), "6"});
    t.add_row({"Section 6", row, "iterations n", rs.cell("steps", r), "7100"});
    t.add_row({"Section 6", row, "coverage %", fixed_cell(pct(rs, r), 2), "91"});
    t.add_row({"Section 6", row, "coverage time to 90% (s, common model)",
               rs.text("status")[r] == "ok" ? sig_cell(rs.num("coverage_time")[r], 5) : "-", "-"});
  }
}

// Figs. 15-16: mirror mapping.
void add_mirror(TextTable& t, const ResultSet& rs) {
  for (std::size_t r : part_rows(rs, "mirror")) {
    const int n = int(rs.num("c3_n")[r]);
    const auto p = paper_mirror.find(n);
    const std::string row = "n = " + std::to_string(n);
    t.add_row({"Mirror mapping", row, "reflections", rs.cell("reflections", r),
               p == paper_mirror.end() ? "-" : std::to_string(p->second.first)});
    t.add_row({"Mirror mapping", row, "coverage %", fixed_cell(pct(rs, r), 2),
               p == paper_mirror.end() ? "-" : fixed_cell(p->second.second, 2)});
  }
}

}  // namespace

TextTable seed003_table(const ResultSet& rs) {
  for (const char* c : {"label", "final_coverage", "start_x", "ds_index", "c3_n", "steps", "segments", "reflections"})
    if (!rs.has(c)) (void)rs.num(c);
  TextTable t;
  t.title = "Seed 003: Tables 1-3, the complete-coverage loop and mirror mapping, paper vs ours";
  t.header = {"table", "row", "quantity", "ours", "paper"};
  add_tables_1_2(t, rs);
  add_table_3(t, rs);
  add_spread(t, rs);
  add_loop(t, rs);
  add_mirror(t, rs);
  if (t.rows.empty())
    throw AnalysisError(
        "no seed 003 rows: give the results of experiments/seed003.toml (labels table1, table3, loop, mirror)");
  t.notes.push_back(
      "Read literally (docs/spec.md §4), the heading depends on the Arnold state only, so the start point merely "
      "translates the trajectory and nothing after Map depends on it: Table 1's ten rows are equal, "
      "where the paper's vary. The loop's candidates therefore come from a grid of Arnold initial "
      "states (docs/seed003.md).");
  return t;
}

}  // namespace chaosweep
