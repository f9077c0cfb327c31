// analysis/: tables and figures from result files. Golden tests run on small
// hand-made result files whose numbers can be checked by hand (the expected
// values are also asserted directly); figure tests render real PNGs.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "analysis/figures.hpp"
#include "analysis/grouping.hpp"
#include "analysis/replay.hpp"
#include "analysis/result_set.hpp"
#include "analysis/tables.hpp"
#include "analysis/tune_table.hpp"
#include "engine/store/h5_store.hpp"
#include "tests/support/test_util.hpp"

namespace chaosweep {
namespace {

using test::TempDir;

constexpr double timeout = std::numeric_limits<double>::infinity();

// One stored row with the given parameters and outcome (ct = timeout for a
// run that missed the target).
RunRow make_row(std::int64_t id, const RunParams& p, const std::string& env, const std::string& label, double ct,
                double t_opt = 2250) {
  RunRow r;
  r.tuple.run_id = id;
  r.tuple.env_spec = env;
  r.tuple.label = label;
  r.tuple.params = p;
  r.result.status = std::isinf(ct) ? Status::timeout : Status::ok;
  r.result.coverage_time = std::isinf(ct) ? std::numeric_limits<double>::quiet_NaN() : ct;
  r.result.t_opt = t_opt;
  r.result.pr = std::isinf(ct) ? std::numeric_limits<double>::quiet_NaN() : ct / t_opt;
  r.result.steps = 100;
  r.result.final_coverage = std::isinf(ct) ? 0.5 : 0.9;
  return r;
}

void write_results(const std::string& path, const std::vector<RunRow>& rows) {
  H5RunWriter w(path);
  w.append(rows);
  w.finish();
}

// Table 1 in miniature: one map (50 m, SR 1, no obstacles), four cases
// labelled as Table 1 rows, two seeds per tuple.
//   row 1 original: ds 1 -> 1000, 1200 (median 1100); ds 2 -> 900, timeout
//                   (median infinite); ds 3 -> 800, 1000 (median 900: best)
//   row 12 IS:      ds 3 -> 700, 800 (750)
//   row 20 MZ:      c 0.1 -> 600, 640 (620); c 0.5 -> 500, 560 (530: best)
//   row 24 SC:      f 1 -> 900, 950 (925); f 2 -> 450, 470 (460: best)
std::vector<RunRow> table1_rows() {
  std::vector<RunRow> rows;
  std::int64_t id = 0;
  auto add = [&](const std::string& label, RunParams p, std::vector<double> cts) {
    p.size_x = p.size_y = 50;
    p.sr = 1;
    for (std::size_t s = 0; s < cts.size(); ++s) {
      p.seed = std::int64_t(s);
      rows.push_back(make_row(id++, p, "no_obstacles", label, cts[s]));
    }
  };
  RunParams p;
  for (auto [ds, a, b] : {std::tuple{1, 1000.0, 1200.0}, {2, 900.0, timeout}, {3, 800.0, 1000.0}}) {
    p.ds_index = ds;
    add("1", p, {a, b});
  }
  p.ds_index = 3;
  p.index_switching = true;
  add("12", p, {700, 800});
  p.index_switching = false;
  p.map_zoning = true;
  p.c = 0.1;
  add("20", p, {600, 640});
  p.c = 0.5;
  add("20", p, {500, 560});
  p.map_zoning = false;
  p.c = 0.25;
  p.f = 1;
  add("24", p, {900, 950});
  p.f = 2;
  add("24", p, {450, 470});
  return rows;
}

// Fig. 6 in miniature: A in {0.4, 0.5}, B in {0.2, 0.3}, C in {0.25, 0.35},
// one run each, budget 5000 s.
std::vector<RunRow> fig6_rows() {
  const std::vector<std::tuple<double, double, double, double>> cts{
      {0.4, 0.2, 0.25, 3000}, {0.4, 0.2, 0.35, 2500}, {0.4, 0.3, 0.25, 2000}, {0.4, 0.3, 0.35, timeout},
      {0.5, 0.2, 0.25, 1500}, {0.5, 0.2, 0.35, 4000}, {0.5, 0.3, 0.25, 3500}, {0.5, 0.3, 0.35, 1000}};
  std::vector<RunRow> rows;
  for (const auto& [a, b, c, ct] : cts) {
    RunParams p;
    p.A = a, p.B = b, p.C = c;
    p.max_time = 5000;
    rows.push_back(make_row(std::int64_t(rows.size()), p, "empty", "", ct));
  }
  return rows;
}

std::string golden_path(const std::string& name) { return std::string(CHAOSWEEP_SOURCE_DIR) + "/tests/golden/" + name; }

// Compares with tests/golden/NAME; CHAOSWEEP_UPDATE_GOLDEN=1 rewrites the
// file instead (then review the diff before committing it).
void expect_golden(const std::string& name, const std::string& actual) {
  const std::string path = golden_path(name);
  if (const char* u = std::getenv("CHAOSWEEP_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    test::write_file(path, actual);
    return;
  }
  std::ifstream in(path);
  ASSERT_TRUE(in) << "missing golden file " << path << " (CHAOSWEEP_UPDATE_GOLDEN=1 writes it)";
  EXPECT_EQ(test::read_file(path), actual) << "differs from " << path;
}

std::string table_text(const std::string& name, const ResultSet& rs, const TableOptions& opt, TableFormat f) {
  std::ostringstream os;
  make_table(name, rs, opt).write(os, f);
  return os.str();
}

class Table1Results : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.file("t1.h5");
    write_results(path_, table1_rows());
    paper_ = dir_.file("paper.csv");
    test::write_file(paper_, "# test\nrow,paper_ct,paper_pr\n1,1000,0.44\n12,750,0.33\n");
  }
  TempDir dir_;
  std::string path_, paper_;
};

TEST_F(Table1Results, Table1PicksTheBestTupleByMedianAndComparesWithTheOriginal) {
  const ResultSet rs = ResultSet::load({path_});
  TableOptions opt;
  opt.paper = paper_;
  const TextTable t = make_table("table1", rs, opt);
  ASSERT_EQ(t.rows.size(), 4u);
  auto col = [&](const std::string& h) {
    return std::size_t(std::find(t.header.begin(), t.header.end(), h) - t.header.begin());
  };
  // Row 1: ds 3 wins with median 900 (ds 2's timeout makes its median infinite).
  EXPECT_EQ(t.rows[0][col("row")], "1");
  EXPECT_EQ(t.rows[0][col("DSindex")], "3");
  EXPECT_EQ(t.rows[0][col("CT (s)")], "900");
  EXPECT_EQ(t.rows[0][col("tuples")], "3");
  EXPECT_EQ(t.rows[0][col("PR")], "0.40");
  EXPECT_EQ(t.rows[0][col("CT / paper")], "0.90");
  // Row 20: c 0.5 with 530 s, (900 - 530) / 900 = 41.1% and 370 s = 0.10 h faster.
  EXPECT_EQ(t.rows[2][col("technique")], "MZ");
  EXPECT_EQ(t.rows[2][col("c")], "0.5");
  EXPECT_EQ(t.rows[2][col("CT (s)")], "530");
  EXPECT_EQ(t.rows[2][col("improvement %")], "41.1");
  EXPECT_EQ(t.rows[2][col("improvement h")], "0.10");
  // Row 24: scaling searched over f = 1, 2: f = 2 wins (460 s, 48.9%).
  EXPECT_EQ(t.rows[3][col("technique")], "SC");
  EXPECT_EQ(t.rows[3][col("f")], "2");
  EXPECT_EQ(t.rows[3][col("improvement %")], "48.9");
  expect_golden("table1.md", table_text("table1", rs, opt, TableFormat::md));
  expect_golden("table1.tex", table_text("table1", rs, opt, TableFormat::tex));
}

TEST_F(Table1Results, SummaryGivesRunsOkRateAndQuantilesPerGroup) {
  const ResultSet rs = ResultSet::load({path_});
  TableOptions opt;
  opt.by = {"label"};
  const TextTable t = make_table("summary", rs, opt);
  ASSERT_EQ(t.rows.size(), 4u);
  // Label 1: 6 runs, 5 ok; CTs 800 900 1000 1000 1200.
  EXPECT_EQ(t.rows[0],
            (std::vector<std::string>{"1", "6", "5", "0.833", "800", "900", "1000", "1000", "1200", "0.444", "0.900"}));
  expect_golden("summary_by_label.csv", table_text("summary", rs, opt, TableFormat::csv));
}

TEST_F(Table1Results, BestRanksTuplesPerGroupAndKeepsTopK) {
  const ResultSet rs = ResultSet::load({path_});
  TableOptions opt;
  opt.by = {"label"};
  opt.params = {"ds_index", "c", "f"};
  opt.top = 2;
  const TextTable t = make_table("best", rs, opt);
  // Label 1 has 3 tuples (top 2 shown), 12 has 1, 20 and 24 have 2 each.
  ASSERT_EQ(t.rows.size(), 7u);
  EXPECT_EQ(t.rows[0][1], "1");  // rank
  EXPECT_EQ(t.rows[0][2], "3");  // ds_index 3: median 900
  EXPECT_EQ(t.rows[1][2], "1");  // ds_index 1: median 1100 (ds 2 is infinite)
  expect_golden("best_by_label.md", table_text("best", rs, opt, TableFormat::md));
}

// summary and best read only the columns they need (table_columns); their
// tables are those of every column loaded, and a missing column is named
// with the files' columns, loaded or not.
TEST(Tables, SummaryBestAndLeaderboardOfTheColumnsTheyNeedAreThoseOfEveryColumn) {
  TempDir dir;
  auto other = table1_rows();  // another file: sr (constant in each file) differs between them
  for (RunRow& r : other) {
    r.tuple.run_id += 1000;
    r.tuple.params.sr = 4;
  }
  write_results(dir.file("a.h5"), table1_rows());
  write_results(dir.file("b.h5"), other);
  for (const std::vector<std::string>& files :
       {std::vector<std::string>{dir.file("a.h5")}, std::vector<std::string>{dir.file("a.h5"), dir.file("b.h5")}}) {
    const ResultSet all = ResultSet::load(files);
    for (const std::string name : {"summary", "best", "leaderboard"}) {
      for (const auto& [by, params] :
           {std::pair<std::string, std::string>{"", ""}, {"label", ""}, {"label", "ds_index,c,f"}, {"env,sr", ""}}) {
        TableOptions opt;
        opt.by = split_list(by);
        opt.params = split_list(params);
        opt.top = 3;
        const TableColumns cols = table_columns(name, opt);
        ASSERT_FALSE(cols.all);
        const ResultSet some = ResultSet::load(files, cols.columns, cols.if_varying);
        EXPECT_LT(some.names().size(), all.names().size());
        EXPECT_EQ(some.file_columns(), all.names());
        EXPECT_EQ(table_text(name, some, opt, TableFormat::csv), table_text(name, all, opt, TableFormat::csv))
            << name << " by " << by << " params " << params << " of " << files.size();
      }
    }
    const ResultSet best = ResultSet::load(files, {}, {"sr", "f", "seed"});  // sr varies only across the files
    EXPECT_EQ(best.has("sr"), files.size() == 2);
    EXPECT_TRUE(best.has("f"));
    if (best.has("sr")) {
      EXPECT_EQ(best.num("sr"), all.num("sr"));
    }
    EXPECT_EQ(best.num("f"), all.num("f"));
  }
  TableOptions opt;
  opt.by = {"colour"};
  const TableColumns cols = table_columns("summary", opt);
  try {
    make_table("summary", ResultSet::load({dir.file("a.h5")}, cols.columns, cols.if_varying), opt);
    FAIL() << "no error";
  } catch (const AnalysisError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no column 'colour'"), std::string::npos) << what;
    EXPECT_NE(what.find("wall_time"), std::string::npos) << "a column not loaded is listed: " << what;
  }
  EXPECT_TRUE(table_columns("table1", opt).all);
}

TEST(Tables, BadNamesAndColumnsAreNamedInTheError) {
  TempDir dir;
  write_results(dir.file("r.h5"), fig6_rows());
  const ResultSet rs = ResultSet::load({dir.file("r.h5")});
  TableOptions opt;
  try {
    make_table("tabel1", rs, opt);
    FAIL() << "no error";
  } catch (const AnalysisError& e) {
    EXPECT_NE(std::string(e.what()).find("allowed: table1, best, summary"), std::string::npos) << e.what();
  }
  opt.by = {"colour"};
  try {
    make_table("summary", rs, opt);
    FAIL() << "no error";
  } catch (const AnalysisError& e) {
    EXPECT_NE(std::string(e.what()).find("no column 'colour'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ResultSet::load({dir.file("missing.h5")}), AnalysisError);
  test::write_file(dir.file("foreign.h5"), "not hdf5");
  EXPECT_THROW(ResultSet::load({dir.file("foreign.h5")}), AnalysisError);
}

TEST(Tables, WhereKeepsTheRowsMatchingEveryCondition) {
  TempDir dir;
  write_results(dir.file("t1.h5"), table1_rows());
  const ResultSet rs = ResultSet::load({dir.file("t1.h5")});
  EXPECT_EQ(rs.where({"label=1"}).rows(), 6u);
  EXPECT_EQ(rs.where({"label=1", "ds_index=3"}).rows(), 2u);
  EXPECT_EQ(rs.where({"status=timeout"}).rows(), 1u);
  EXPECT_EQ(rs.where({"c=0.5"}).rows(), 2u);
  EXPECT_THROW(rs.where({"ds_index=three"}), AnalysisError);
  EXPECT_THROW(rs.where({"colour=red"}), AnalysisError);
  EXPECT_THROW(rs.where({"label"}), AnalysisError);
}

// A --where that keeps nothing says which condition, and what the column
// holds, instead of "the result files hold no runs".
TEST(Tables, WhereThatMatchesNothingSaysSoNamingTheConditionAndTheValues) {
  TempDir dir;
  write_results(dir.file("t1.h5"), table1_rows());
  const ResultSet rs = ResultSet::load({dir.file("t1.h5")});
  auto message = [&](const std::vector<std::string>& conditions) {
    try {
      (void)rs.where(conditions);
    } catch (const AnalysisError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({"c=0.33"}), "--where c=0.33 matches none of the 16 runs: c takes 0.1, 0.25, 0.5");
  EXPECT_EQ(message({"label=1", "env=nowhere"}),
            "--where env=nowhere matches none of the 16 runs: env takes 'no_obstacles'");
  EXPECT_EQ(message({"label=12", "c=0.5"}),
            "--where label=12 --where c=0.5: no run matches them all (each alone matches some of the 16 runs)");
  const std::string h5 = dir.file("t1.h5");
  for (const std::string& cmd :
       {"table best " + h5 + " --where c=0.33", "figure fig6a " + h5 + " --where c=0.33 -o " + dir.file("f.png")}) {
    const auto r = test::run_chaosweep(cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_NE(r.err.find(": --where c=0.33 matches none of the 16 runs: c takes 0.1, 0.25, 0.5\n"), std::string::npos)
        << cmd << "\n"
        << r.err;
    EXPECT_EQ(r.err.find("hold no runs"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("f.png")));
}

TEST(Tables, ResultsOfSeveralFilesAreReadAsOne) {
  TempDir dir;
  auto rows = table1_rows();
  write_results(dir.file("a.h5"), {rows.begin(), rows.begin() + 6});
  write_results(dir.file("b.h5"), {rows.begin() + 6, rows.end()});
  write_results(dir.file("all.h5"), rows);
  TableOptions opt;
  EXPECT_EQ(table_text("table1", ResultSet::load({dir.file("a.h5"), dir.file("b.h5")}), opt, TableFormat::md),
            table_text("table1", ResultSet::load({dir.file("all.h5")}), opt, TableFormat::md));
}

TEST(Tables, Seed001NeedsNoResultsAndShowsThePapersValues) {
  const auto r = test::run_chaosweep("table seed001 --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("quantity,n,ours,paper,note\n", 0), 0u) << r.out;
  // CSV carries our numbers in full (Markdown shows 1.7918), the paper's as printed.
  EXPECT_NE(r.out.find("\"Lyapunov exponent, raw map\",1000000,1.79175889"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(",1.7918,ln 6 = 1.7918\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(",0.8309,"), std::string::npos);
  const auto bad = test::run_chaosweep("table summary");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("give one or more result files"), std::string::npos) << bad.err;
}

// Seed 003's robot and workplace (experiments/seed003.toml's [fixed]).
constexpr const char* seed003_robot = R"(
[fixed]
planner = "contraction"
size = 20
sr = 1
A = 1
B = 0.5
C = 0.5
ic = [4, 3.5, 0]
)";

TEST(Tables, Seed003ComparesTablesOneToThreeLoopAndMirrorWithThePaper) {
  TempDir dir;
  // experiments/seed003.toml in miniature: the same parts, fewer values.
  test::write_file(dir.file("s.toml"), std::string(seed003_robot) + R"(
[[part]]
name = "table1"
fixed = { c3_mode = "map", c3_n = 800 }
[[part.zip]]
start = [[0, 0], [8, 8]]
[part.axes]
ds_index = [1, 2, 3]
[[part]]
name = "table3"
fixed = { c3_mode = "map", start = [10, 10], ds_index = 3, c3_n = 800 }
[[part]]
name = "loop"
fixed = { c3_mode = "loop", start = [10, 10], ds_index = 3 }
[[part]]
name = "mirror"
fixed = { c3_mode = "mirror", start = [10, 10], ds_index = 3, c3_n = 779 }
)");
  auto r = test::run_chaosweep("sweep " + dir.file("s.toml") + " -o " + dir.file("r.h5") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run_chaosweep("table seed003 " + dir.file("r.h5") + " --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Heading z from (8, 8) at n = 800: ours 30.75% (any start: docs/seed003.md), paper 49%.
  EXPECT_NE(r.out.find("Table 1,\"(8, 8)\",\"coverage % at n = 800, heading z\",30.75,49\n"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("Table 2,heading z,mean coverage %,30.75,47.6\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Table 3,n = 800,\"coverage % from (10, 10), heading z\",30.75,54.5\n"), std::string::npos);
  EXPECT_NE(r.out.find("Section 6,ic grid step 1,sections,8,6"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Mirror mapping,n = 779,coverage %,16.75,16.75"), std::string::npos) << r.out;
  r = test::run_chaosweep("table seed003 " + dir.file("r.h5") + " --where label=nothing");
  EXPECT_EQ(r.exit_code, 2);
}

TEST(Tables, Seed003SpreadGivesTable2OverJitteredSamplesAndTable3sCollapseShare) {
  TempDir dir;
  // experiments/seed003_spread.toml in miniature: 8 samples, ic +-1e-6 and +-1.
  test::write_file(dir.file("s.toml"), std::string(seed003_robot) + R"(
c3_mode = "map"
start = [10, 10]
[axes]
ic_jitter = [1e-6, 1]
seed = { start = 0, stop = 7, step = 1 }
[[part]]
name = "table1-spread"
fixed = { c3_n = 800, ds_index = 3 }
[[part]]
name = "table3-spread"
fixed = { ds_index = 3, c3_n = 19200 }
)");
  auto r = test::run_chaosweep("sweep " + dir.file("s.toml") + " -o " + dir.file("r.h5") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run_chaosweep("table seed003 " + dir.file("r.h5") + " --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // A 1e-6 perturbation does not grow within 800 steps: the literal model's
  // 30.75% every time, sd 0 (the paper's Table 2: 47.6, sd 8.0).
  EXPECT_NE(r.out.find("Table 2 (spread),\"heading z, ic +-1e-06, 8 samples\",mean coverage %,30.75,47.6\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("Table 2 (spread),\"heading z, ic +-1e-06, 8 samples\",standard deviation (n - 1),0,8.0062\n"),
            std::string::npos)
      << r.out;
  // A perturbation of 1 gives each sample its own trajectory, hence a spread.
  const std::string sd1 = "Table 2 (spread),\"heading z, ic +-1, 8 samples\",standard deviation (n - 1),";
  const auto at = r.out.find(sd1);
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_GT(std::stod(r.out.substr(at + sd1.size())), 1.0);
  EXPECT_NE(r.out.find("Table 3 (spread),\"n = 19200, ic +-1, 8 samples\",share of samples at <= 12% (collapsed),"),
            std::string::npos)
      << r.out;
}

TEST(Tables, Seed002GivesAMixtureOnTheSimplexAndThePlansByAngles) {
  const auto r = test::run_chaosweep("table seed002 --bins 24 --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Both fits of Eq. 5: over the configurations (as written) and over the
  // position cells; each alpha on the simplex.
  std::map<std::string, std::vector<double>> alpha;
  std::istringstream in(r.out);
  std::string line;
  while (std::getline(in, line))
    for (const char* space : {"configurations", "position cells"})
      if (line.rfind(std::string("mixture weight alpha fitted on ") + space, 0) == 0) {
        const std::string rest = line.substr(line.find(" deg,") + 5);
        alpha[space].push_back(std::stod(rest.substr(0, rest.find(','))));
      }
  ASSERT_EQ(alpha.size(), 2u) << r.out;
  for (const auto& [space, a] : alpha) {
    ASSERT_EQ(a.size(), 3u) << space;
    double sum = 0;
    for (double x : a) {
      EXPECT_GE(x, 0.0) << space;
      sum += x;
    }
    EXPECT_NEAR(sum, 1.0, 2e-3) << space;  // printed to 3 decimals
  }
  // On this map the fits differ: over positions the 75-degree policy alone
  // (a vertex), over configurations a mixture of two.
  EXPECT_EQ(alpha["position cells"], (std::vector<double>{0, 1, 0}));
  EXPECT_GT(alpha["configurations"][1], 0.0);
  EXPECT_GT(alpha["configurations"][2], 0.0);
  EXPECT_NE(r.out.find(",0.221"), std::string::npos);  // the paper's, beside ours
  // Plans by angles used: ours and the paper's navigation setting.
  EXPECT_NE(r.out.find("plans using 1 bouncing angle (%),\"{30, 75, 315} deg, 24 bins, w2 2, 64 sources\","),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("plans using 3 bouncing angles (%),\"{45, 90, 135} deg, 8 bins, w2 100, 1464 sources\","),
            std::string::npos)
      << r.out;
}

TEST(Grouping, QuantileInterpolatesLikeNumpy) {
  EXPECT_EQ(quantile({1, 2, 3, 4}, 0.5), 2.5);
  EXPECT_EQ(quantile({1, 2, 3, 4}, 0.25), 1.75);
  EXPECT_EQ(quantile({7}, 0.75), 7);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

TEST(TextTables, CsvQuotesAndTexEscapes) {
  TextTable t;
  t.header = {"name", "value"};
  t.add_row({"a,b", "say \"hi\""});
  t.add_row({"x_1 & 50%", "3"});
  std::ostringstream csv, tex;
  t.write(csv, TableFormat::csv);
  t.write(tex, TableFormat::tex);
  EXPECT_EQ(csv.str(), "name,value\n\"a,b\",\"say \"\"hi\"\"\"\nx_1 & 50%,3\n");
  EXPECT_NE(tex.str().find("x\\_1 \\& 50\\% & 3 \\\\"), std::string::npos) << tex.str();
  EXPECT_THROW(t.add_row({"only one"}), std::logic_error);
  EXPECT_THROW(parse_table_format("html"), AnalysisError);
}

// ------------------------------------------------------------------ figures

struct Png {
  int width = 0, height = 0;
  std::size_t colours = 0;
  double non_white = 0;  // share of pixels that are not white
};

Png read_png(const std::string& path) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) return {};
  img.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> px(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, px.data(), 0, nullptr)) return {};
  Png out{int(img.width), int(img.height), 0, 0};
  std::set<unsigned> colours;
  std::size_t non_white = 0;
  for (std::size_t i = 0; i + 2 < px.size(); i += 3) {
    colours.insert(unsigned(px[i]) << 16 | unsigned(px[i + 1]) << 8 | px[i + 2]);
    non_white += !(px[i] == 255 && px[i + 1] == 255 && px[i + 2] == 255);
  }
  out.colours = colours.size();
  out.non_white = double(non_white) / double(px.size() / 3);
  return out;
}

void expect_drawn(const std::string& png, int w, int h) {
  const Png p = read_png(png);
  EXPECT_EQ(p.width, w) << png;
  EXPECT_EQ(p.height, h) << png;
  EXPECT_GT(p.colours, 8u) << png << ": a blank or single-colour image";
  EXPECT_GT(p.non_white, 0.03) << png << ": almost nothing drawn";
}

TEST(Tables, ReadingsGiveEachRowsRangeAndTheObstacleToOpenRatioBesideThePapers) {
  // Row 9 (200 m, SR 4, open) ran once, under push; row 10 (its five-obstacle
  // case) under push and mirror. Paper: 53,600 s and 35,100 s (ratio 0.655).
  TempDir dir;
  std::vector<RunRow> rows;
  auto add = [&](const std::string& label, const std::string& env, ObstacleResponse resp, std::vector<double> cts) {
    RunParams p;
    p.size_x = p.size_y = 200;
    p.sr = 4;
    p.obstacle_response = resp;
    for (std::size_t s = 0; s < cts.size(); ++s) {
      p.seed = std::int64_t(s);
      rows.push_back(make_row(std::int64_t(rows.size()), p, env, label, cts[s]));
      rows.back().result.free_cells = env == "no_obstacles" ? 2500 : 1472;
    }
  };
  add("9", "no_obstacles", ObstacleResponse::push, {50000, 60000});
  add("10", "five_squares", ObstacleResponse::push, {40000, 44000});
  add("10", "five_squares", ObstacleResponse::mirror, {30000, 38000, timeout});
  write_results(dir.file("r.h5"), rows);
  test::write_file(dir.file("paper.csv"), "row,paper_ct,paper_pr\n9,53600,6.0\n10,35100,6.6\n");
  TableOptions opt;
  opt.paper = dir.file("paper.csv");
  const TextTable t = make_table("readings", ResultSet::load({dir.file("r.h5")}), opt);
  ASSERT_EQ(t.header[0], "reading");
  ASSERT_EQ(t.rows.size(), 3u);
  auto col = [&](const std::string& name) {
    return std::size_t(std::find(t.header.begin(), t.header.end(), name) - t.header.begin());
  };
  // In run order: the defaults (rows 9 and 10), then mirror.
  const auto& mirror = t.rows[2];
  EXPECT_EQ(mirror[0], "obstacle_response=mirror");  // what differs from the defaults
  EXPECT_EQ(t.rows[0][0], "defaults");
  EXPECT_EQ(mirror[col("row")], "10");
  EXPECT_EQ(mirror[col("ok")], "2/3");
  EXPECT_EQ(mirror[col("median CT")], "38000");  // the timeout counts as infinite
  EXPECT_EQ(mirror[col("paper in [min, max]")], "yes");
  EXPECT_EQ(mirror[col("open row")], "9");            // the push reading's: an open map has no obstacle to respond to
  EXPECT_EQ(mirror[col("CT / open")], "0.69");        // 38000 / 55000
  EXPECT_EQ(mirror[col("paper CT / open")], "0.65");  // 35100 / 53600
  EXPECT_EQ(mirror[col("ratio / paper's")], "1.06");
  // Resampling {30000, 38000, inf} and {50000, 60000}: the ratio's median
  // spans 30000/60000 to inf (two of three resampled runs timing out).
  EXPECT_EQ(mirror[col("ratio / paper's, 90% interval")], "-");
  EXPECT_EQ(t.rows[0][col("row")], "9");
  EXPECT_EQ(t.rows[0][col("open row")], "-");
  const auto& push = t.rows[1];
  EXPECT_EQ(push[col("row")], "10");
  EXPECT_EQ(push[col("paper in [min, max]")], "no");  // 35,100 below our min 40,000
  EXPECT_EQ(push[col("CT / open")], "0.76");
  // 40000/60000 to 44000/50000 over 0.655: [1.02, 1.34].
  EXPECT_EQ(push[col("ratio / paper's, 90% interval")], "[1.02, 1.34]");
}

// A parameter is printed as the double it is (0.1 + 0.2 is not 0.3), in every
// table and figure CSV; computed numbers are rounded for reading in Markdown
// but carried in full in CSV.
TEST(Tables, ParametersPrintInShortestRoundTripFormAndCsvCarriesFullPrecision) {
  TempDir dir;
  std::vector<RunRow> rows;
  RunParams p;
  p.A = 0.5, p.B = 0.2, p.C = 0.1 + 0.2;
  rows.push_back(make_row(0, p, "empty", "", 1185.0999999999999));
  p.C = 0.3;
  rows.push_back(make_row(1, p, "empty", "", 3828.6123456789));
  p.A = 0.6;  // a second column of the heatmap
  rows.push_back(make_row(2, p, "empty", "", timeout));
  p.C = 0.1 + 0.2;
  rows.push_back(make_row(3, p, "empty", "", timeout));
  write_results(dir.file("r.h5"), rows);
  const ResultSet rs = ResultSet::load({dir.file("r.h5")});
  TableOptions opt;
  opt.params = {"A", "B", "C"};
  const std::string md = table_text("best", rs, opt, TableFormat::md);
  EXPECT_NE(md.find("| 1 | 0.5 | 0.2 | 0.30000000000000004 | 1185.1 | 1185.1 | 1/1 | 0.527 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| 2 | 0.5 | 0.2 | 0.3 | 3828.6 | 3828.6 | 1/1 | 1.7 |"), std::string::npos) << md;
  const std::string csv = table_text("best", rs, opt, TableFormat::csv);
  EXPECT_NE(csv.find("\n1,0.5,0.2,0.30000000000000004,1185.1,1185.1,1/1,0.526711111111111\n"), std::string::npos)
      << csv;
  EXPECT_NE(csv.find("\n2,0.5,0.2,0.3,3828.6123456789,3828.6123456789,1/1,"), std::string::npos) << csv;
  FigureOptions fo;
  fo.size = {320, 240};
  const FigureOutput out = make_figure("fig6a", rs, fo, dir.file("a.png"));
  EXPECT_EQ(test::read_file(out.csv),
            "A,C,min_ct,runs,ok\n0.5,0.3,3828.6123456789,1,1\n0.5,0.30000000000000004,1185.1,1,1\n"
            "0.6,0.3,-,1,0\n0.6,0.30000000000000004,-,1,0\n");
}

// The names `name` lists in `table --help` / `figure --help` (its one line:
// "a, b or c").
std::vector<std::string> help_names(const std::string& help) {
  const auto at = help.find("  name TEXT REQUIRED");
  EXPECT_NE(at, std::string::npos) << help;
  if (at == std::string::npos) return {};
  std::string line = help.substr(at + 20, help.find('\n', at) - at - 20);
  line = std::regex_replace(line, std::regex(" or "), ", ");
  std::vector<std::string> out;
  for (const std::string& n : split_list(line)) out.push_back(n);
  return out;
}

// The one-line lists of names in --help are the code's own lists, and the
// longer descriptions below them cover every name.
TEST(Help, TableAndFigureNameListsHoldEveryNameTheCommandsAccept) {
  for (const auto& [command, names] :
       {std::pair{std::string("table"), table_names()}, std::pair{std::string("figure"), figure_names()}}) {
    const auto r = test::run_chaosweep(command + " --help");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(help_names(r.out), names) << r.out;
    const std::string footer = r.out.substr(r.out.find(command == "table" ? "\nTables:" : "\nFigures"));
    for (const std::string& n : names) {
      EXPECT_TRUE(std::regex_search(footer, std::regex("\n  (\\w+, )*" + n + "[ ,]"))) << n << " is not described:\n"
                                                                                       << footer;
      // Accepted: naming it is never "unknown" (tables and figures alike need results or not).
      EXPECT_NO_THROW((void)(command == "table" ? table_needs_results(n) : figure_needs_results(n))) << n;
    }
  }
  // The statistics --stat takes, too.
  const auto r = test::run_chaosweep("figure --help");
  EXPECT_NE(r.out.find("statistic, min, q1, median, mean, q3, max, ok_rate or runs"), std::string::npos) << r.out;
  EXPECT_EQ(statistic_names(),
            (std::vector<std::string>{"min", "q1", "median", "mean", "q3", "max", "ok_rate", "runs"}));
  EXPECT_THROW(table_needs_results("nosuch"), AnalysisError);
  EXPECT_THROW(figure_needs_results("nosuch"), AnalysisError);
}

class Fig6Results : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.file("fig6.h5");
    write_results(path_, fig6_rows());
    opt_.size = {640, 480};
  }
  FigureOutput draw(const std::string& name, const std::string& file) {
    return make_figure(name, ResultSet::load({path_}), opt_, dir_.file(file));
  }
  TempDir dir_;
  std::string path_;
  FigureOptions opt_;
};

TEST_F(Fig6Results, Fig6aIsTheMinimumOverBPerAAndC) {
  const FigureOutput out = draw("fig6a", "fig6a.png");
  EXPECT_EQ(out.csv, dir_.file("fig6a.csv"));
  const std::string csv = test::read_file(out.csv);
  // min over B: (0.4, 0.25) 2000; (0.4, 0.35) 2500 (the other timed out); (0.5, 0.25) 1500; (0.5, 0.35) 1000.
  EXPECT_EQ(csv, "A,C,min_ct,runs,ok\n0.4,0.25,2000,2,2\n0.4,0.35,2500,2,1\n0.5,0.25,1500,2,2\n0.5,0.35,1000,2,2\n");
  expect_golden("fig6a.csv", csv);
  expect_drawn(out.image, 640, 480);
}

TEST_F(Fig6Results, Fig6bRanksTheMarkedTupleAmongAllTuples) {
  opt_.mark = {0.5, 0.2, 0.25};
  const FigureOutput out = draw("fig6b", "fig6b.png");
  // Sorted CTs 1000 1500 2000 2500 3000 3500 4000 (and one timeout): the
  // marked tuple's 1500 s is reached by 2 of 8 tuples.
  ASSERT_EQ(out.lines.size(), 1u);
  EXPECT_EQ(out.lines[0], "tuple (0.5, 0.2, 0.25): median CT 1500 s; 25.0% of 8 tuples are at least as fast (rank 2)");
  expect_golden("fig6b.csv", test::read_file(out.csv));
  expect_drawn(out.image, 640, 480);
}

TEST_F(Fig6Results, Fig6bFallsBackToTheNearestGridTupleAndSaysSo) {
  opt_.mark = {0.5, 0.21, 0.25};
  const FigureOutput out = draw("fig6b", "near.png");
  ASSERT_EQ(out.lines.size(), 1u);
  EXPECT_EQ(out.lines[0].rfind("nearest grid tuple to (0.5, 0.21, 0.25): (0.5, 0.2, 0.25)", 0), 0u) << out.lines[0];
}

TEST_F(Fig6Results, HeatmapOfOkRateOverTwoAxes) {
  opt_.x = "A";
  opt_.y = "B";
  opt_.stat = "ok_rate";
  const FigureOutput out = draw("heatmap", "ok.svg");
  EXPECT_EQ(test::read_file(out.csv),
            "A,B,ok_rate,runs,ok\n0.4,0.2,1,2,2\n0.4,0.3,0.5,2,1\n0.5,0.2,1,2,2\n0.5,0.3,1,2,2\n");
  EXPECT_NE(test::read_file(out.image).find("<svg"), std::string::npos);
}

TEST_F(Fig6Results, EveryImageFormatIsWrittenAndOthersAreRefused) {
  for (const char* f : {"a.png", "a.svg", "a.pdf", "a.eps"}) {
    draw("fig6a", f);
    EXPECT_GT(std::filesystem::file_size(dir_.file(f)), 1000u) << f;
  }
  EXPECT_FALSE(std::filesystem::exists(dir_.file("a.prc")));  // the PDF's intermediate is removed
  try {
    draw("fig6a", "a.jpg");
    FAIL() << "no error";
  } catch (const AnalysisError& e) {
    EXPECT_NE(std::string(e.what()).find("allowed: .png, .svg, .pdf, .eps"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_.file("a.csv")) && !std::filesystem::exists(dir_.file("a.png")));
  EXPECT_THROW(parse_image_size("640"), AnalysisError);
  EXPECT_THROW(parse_image_size("50x50"), AnalysisError);
}

TEST(ChebyshevFigures, HistogramAndLyapunovNeedNoResultsAndDrawTheirData) {
  TempDir dir;
  FigureOptions opt;
  const FigureOutput h = make_figure("cheb_histogram", ResultSet{}, opt, dir.file("h.png"));
  ASSERT_EQ(h.lines.size(), 1u);
  EXPECT_NE(h.lines[0].find("arcsine-transformed"), std::string::npos);
  expect_drawn(h.image, 800, 600);
  const FigureOutput l = make_figure("cheb_lyapunov", ResultSet{}, opt, dir.file("l.png"));
  const std::string csv = test::read_file(l.csv);
  EXPECT_NE(csv.find("\n6,1.7917"), std::string::npos) << csv;  // ln 6 = 1.79176
  expect_drawn(l.image, 800, 600);
}

TEST(Seed002Figures, LimitingDistributionHeatmapHasACellPerFreeCell) {
  TempDir dir;
  FigureOptions opt;
  opt.bins = 24;
  const FigureOutput f = make_figure("seed002_limit", ResultSet{}, opt, dir.file("lim.png"));
  std::istringstream in(test::read_file(f.csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,mixture,policy_30,policy_75,policy_315");
  int rows = 0;
  double sum = 0;
  while (std::getline(in, line)) {
    ++rows;
    sum += std::stod(line.substr(line.find(',', line.find(',') + 1) + 1));
  }
  EXPECT_EQ(rows, 183);  // the map's free cells
  EXPECT_NEAR(sum, 1.0, 1e-3);
  expect_drawn(f.image, 800, 600);
  opt.policy = 2;  // the 75-degree policy alone
  EXPECT_EQ(test::read_file(make_figure("seed002_limit", ResultSet{}, opt, dir.file("p2.png")).csv).substr(0, 20),
            "x,y,shown_policy,pol");
  opt.policy = 4;
  EXPECT_THROW(make_figure("seed002_limit", ResultSet{}, opt, dir.file("p4.png")), AnalysisError);
}

// Trajectory and coverage figures replay real runs: a small sweep on a 12 m
// map, one run with map zoning so that transits and zone midpoints appear.
class ReplayedRuns : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    test::write_file(dir_->file("spec.toml"), R"([sweep]
name = "replay"
[fixed]
size = 12
sr = 1
max_time = 3000
[axes]
map_zoning = [0, 1]
A = [0.45, 0.5]
)");
    const auto r = test::run_chaosweep("sweep " + dir_->file("spec.toml") + " -o " + dir_->file("r.h5") + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  static void TearDownTestSuite() { delete dir_; }
  static TempDir* dir_;
};
TempDir* ReplayedRuns::dir_ = nullptr;

TEST_F(ReplayedRuns, TrajectoryReplaysTheStoredRunExactly) {
  const ResultSet rs = ResultSet::load({dir_->file("r.h5")});
  FigureOptions opt;
  opt.runs = {3};  // map zoning, A = 0.5
  opt.size = {700, 700};
  const FigureOutput out = make_figure("trajectory", rs, opt, dir_->file("traj.png"));
  EXPECT_TRUE(out.lines.empty()) << out.lines[0];  // no replay mismatch
  const std::string csv = test::read_file(out.csv);
  std::istringstream in(csv);
  std::string line, last;
  std::size_t n = 0, transits = 0;
  std::getline(in, line);
  EXPECT_EQ(line, "t,x,y,kind,ds_index,visited_cells");
  while (std::getline(in, line)) {
    if (n == 0) {
      EXPECT_NE(line.find(",start,"), std::string::npos) << line;
    }
    transits += line.find(",transit,") != std::string::npos;
    last = line;
    ++n;
  }
  const std::size_t r = row_of_run(rs, 3);
  EXPECT_EQ(double(n - 1 - transits), rs.num("steps")[r]);  // every integration step, plus the start
  EXPECT_EQ(last.substr(last.rfind(',') + 1), rs.cell("visited_cells", r));
  expect_drawn(out.image, 700, 700);
}

TEST_F(ReplayedRuns, CoverageCurvesRiseToEachRunsFinalCoverage) {
  const ResultSet rs = ResultSet::load({dir_->file("r.h5")});
  FigureOptions opt;
  opt.by = "map_zoning";  // the median run of each
  const FigureOutput out = make_figure("coverage", rs, opt, dir_->file("cov.png"));
  std::istringstream in(test::read_file(out.csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "run_id,t,coverage_percent");
  std::set<std::string> runs;
  double prev = -1;
  std::string prev_run;
  while (std::getline(in, line)) {
    const std::string run = line.substr(0, line.find(','));
    const double pct = std::stod(line.substr(line.rfind(',') + 1));
    if (run == prev_run) {
      EXPECT_GE(pct, prev) << line;  // never decreases
    }
    runs.insert(run);
    prev = pct, prev_run = run;
  }
  EXPECT_EQ(runs.size(), 2u);
  expect_drawn(out.image, 800, 600);
}

TEST_F(ReplayedRuns, CommandLineWritesImageAndCsvAndRejectsBadInput) {
  const std::string h5 = dir_->file("r.h5");
  auto r = test::run_chaosweep("figure fig6b " + h5 + " -o " + dir_->file("cli.png") + " --mark 0.5,0.25,0.25");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir_->file("cli.png")));
  EXPECT_TRUE(std::filesystem::exists(dir_->file("cli.csv")));
  r = test::run_chaosweep("table summary " + h5 + " --by map_zoning --format csv");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("map_zoning,runs,ok,", 0), 0u) << r.out;
  r = test::run_chaosweep("table nosuch " + h5);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown table 'nosuch'"), std::string::npos) << r.err;
  r = test::run_chaosweep("figure heatmap " + h5 + " --x A --y colour -o " + dir_->file("h.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no column 'colour'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_->file("h.png")));
  r = test::run_chaosweep("figure trajectory " + h5 + " --run 99 -o " + dir_->file("t.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no run with run_id 99"), std::string::npos) << r.err;
}

// The leaderboard on hand-made rows: two maps, three planners. On map A, p1
// wins (median 100), p2 and p3 tie (every run short of the target: infinite)
// and share ranks 2 and 3 as 2.5; on map B, p2 wins and p1 is second; p3
// never ran there. Metrics are medians over all runs; a file without the
// path metrics shows "-".
TEST(Tables, LeaderboardRanksPlannersPerMapWithSharedTiesAndAMeanRank) {
  const std::vector<std::string> label{"p1", "p1", "p2", "p2", "p3", "p1", "p1", "p2", "p2"};
  const std::vector<std::string> status{"ok", "ok", "timeout", "timeout", "timeout", "ok", "ok", "ok", "ok"};
  const std::vector<std::string> env{"A", "A", "A", "A", "A", "B", "B", "B", "B"};
  const double n = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, std::vector<double>> num{{"coverage_time", {90, 110, n, n, n, 300, 500, 200, 260}},
                                                 {"pr", {0.9, 1.1, n, n, n, 3, 5, 2, 2.6}},
                                                 {"final_coverage", {0.9, 0.9, 0.5, 0.7, 0.4, 0.9, 0.9, 0.9, 0.9}},
                                                 {"size_x", std::vector<double>(9, 50)},
                                                 {"size_y", std::vector<double>(9, 50)},
                                                 {"sr", std::vector<double>(9, 1)}};
  const ResultSet without = ResultSet::from_columns(num, {{"label", label}, {"status", status}, {"env", env}});
  num["visit_evenness"] = {0.8, 0.9, 0.5, 0.7, 0.6, 0.9, 0.9, 0.95, 0.97};
  num["turn_entropy"] = {1.5, 1.6, 1.0, 1.2, 1.1, 1.7, 1.7, 1.8, 1.9};
  num["coverage_area"] = {0.4, 0.6, 9.0, 11.0, n, 1.0, 2.0, 0.75, 1.25};  // NaN: an invalid run's
  const ResultSet rs = ResultSet::from_columns(num, {{"label", label}, {"status", status}, {"env", env}});
  const std::string md = table_text("leaderboard", rs, TableOptions{}, TableFormat::md);
  EXPECT_NE(md.find("| A 50 m, SR 1 | 1 | p1 | 2 | 1.000 | 100 | 1 | 0.900 | 0.850 | 1.550 | 0.500 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| A 50 m, SR 1 | 2.5 | p2 | 2 | 0.000 | - | - | 0.600 | 0.600 | 1.100 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| A 50 m, SR 1 | 2.5 | p3 | 1 | 0.000 | - | - | 0.400 | 0.600 | 1.100 | - |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| B 50 m, SR 1 | 1 | p2 | 2 | 1.000 | 230 | 2.3 | 0.900 | 0.960 | 1.850 | 1.000 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| B 50 m, SR 1 | 2 | p1 | 2 | 1.000 | 400 | 4 |"), std::string::npos) << md;
  // p1: (1 + 2) / 2 = 1.5, one win; p2: (2.5 + 1) / 2 = 1.75, one win; p3: 2.5 on one map.
  EXPECT_NE(md.find("Overall, mean rank over the 2 map(s) (wins): p1 1.5 (1); p2 1.75 (1); p3 2.5 (0) on 1 map(s)."),
            std::string::npos)
      << md;
  const std::string old = table_text("leaderboard", without, TableOptions{}, TableFormat::csv);
  EXPECT_NE(old.find("\"A 50 m, SR 1\",1,p1,2,1,100,1,0.9,-,-,-\n"), std::string::npos) << old;
  // --by names the planner columns; a map column the files lack is named.
  TableOptions by_env;
  by_env.by = {"env"};
  EXPECT_NE(table_text("leaderboard", rs, by_env, TableFormat::md).find("| B 50 m, SR 1 | 1 | B |"), std::string::npos);
  const ResultSet no_sr = ResultSet::from_columns({{"coverage_time", {1}}}, {{"status", {"ok"}}, {"env", {"A"}}});
  EXPECT_THROW(table_text("leaderboard", no_sr, TableOptions{}, TableFormat::md), AnalysisError);
}

// table tune beside a grid's validated best: per case the paired Wilcoxon
// test on the validation seeds the two share. Case "a": the tuner's choice
// is faster on every one of 20 seeds; "b": the two alternate, each ahead on
// half the seeds by the same amounts; "c": the grid's is faster on every
// seed, and one of the tuner's runs missed the target.
TEST(Tables, TuneTablePairsTheTunersChoiceWithTheGridsBestOnTheirSeeds) {
  std::map<std::string, std::vector<double>> num;
  std::vector<std::string> label, status;
  const auto add = [&](const std::string& l, double round, double config, double seed, double ct, bool ok = true) {
    label.push_back(l);
    status.push_back(ok ? "ok" : "timeout");
    num["run_id"].push_back(double(label.size()));
    num["race_round"].push_back(round);
    num["config_id"].push_back(config);
    num["seed"].push_back(seed);
    num["coverage_time"].push_back(ok ? ct : std::numeric_limits<double>::quiet_NaN());
    num["c"].push_back(config == 2 ? 0.5 : 0.25);
  };
  for (const std::string l : {"a", "b", "c"}) {
    add(l, 1, 1, 0, 100);  // two race rows
    add(l, 1, 2, 0, 100);
    // Validation on seeds 1000-1019, the grid's CT 1000 + 10 k on seed
    // 1000 + k; the grid's rows in reverse order, so that only pairing by
    // seed lines the two up.
    for (int k = 0; k < 20; ++k) {
      const double grid = 1000 + 10 * k;
      const double mine = l == "a" ? grid - 30 : l == "b" ? grid + (k % 2 ? 50 : -50) : grid + 100;
      add(l, 0, 1, 1000 + k, mine, !(l == "c" && k == 3));
    }
    for (int k = 19; k >= 0; --k) add(l, 0, 0, 1000 + k, 1000 + 10 * k);
  }
  const ResultSet rs = ResultSet::from_columns(num, {{"label", label}, {"status", status}});
  std::ostringstream md;
  tune_table(rs, nullptr, TuneTableOptions{}).write(md, TableFormat::md);
  const std::string out = md.str();
  const auto row_of = [&](const std::string& l) {
    const std::size_t at = out.find("\n| " + l + " |");
    return at == std::string::npos ? std::string() : out.substr(at + 1, out.find('\n', at + 1) - at - 1);
  };
  EXPECT_NE(row_of("a").find("| tuner better (p "), std::string::npos) << out;
  EXPECT_NE(row_of("b").find("| no difference (p "), std::string::npos) << out;
  EXPECT_NE(row_of("c").find("| grid better (p "), std::string::npos) << out;
  EXPECT_NE(out.find("tuner better in 1, grid better in 1, no difference in 1 of 3 cases"), std::string::npos) << out;
  // Validation rows on other seeds than the grid's cannot be paired: "-".
  std::map<std::string, std::vector<double>> moved = num;
  for (std::size_t r = 0; r < label.size(); ++r)
    if (label[r] == "a" && moved["race_round"][r] == 0 && moved["config_id"][r] == 1) moved["seed"][r] += 100;
  std::ostringstream md2;
  tune_table(ResultSet::from_columns(moved, {{"label", label}, {"status", status}}), nullptr, TuneTableOptions{})
      .write(md2, TableFormat::md);
  EXPECT_NE(md2.str().find("| yes | - |"), std::string::npos) << md2.str();
  EXPECT_NE(md2.str().find("no difference in 1 of 2 cases"), std::string::npos) << md2.str();
}

}  // namespace
}  // namespace chaosweep
