// `chaosweep run --from RESULTS.h5 --run-id N`: a stored row re-run from its
// own columns, compared bit for bit; and a printed tuple typed back into
// `run` reproducing the stored row.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <regex>
#include <set>
#include <sstream>

#include "engine/run/serial_batch_evaluator.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/stored_run.hpp"
#include "tests/support/sweep_rows.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

const std::string source_dir = CHAOSWEEP_SOURCE_DIR;

using chaosweep::test::has;

void write_rows(const std::string& path, const std::vector<RunRow>& rows) {
  H5RunWriter w(path);
  w.append(rows);
  w.finish();
}

// Rows of a small spec whose fixed settings are far from the defaults, so a
// re-run that took anything from the defaults (or from a spec) would differ.
std::vector<RunRow> odd_rows() {
  const SweepSpec spec = parse_sweep_spec(R"(
[fixed]
size = [14, 11]
sr = 1.5
dc = 0.8
max_time = 3000
start = [2.25, 3.5]
ic = [0.1, 0.9, 0.2]
integrator = "rk4-doubling"
label = "odd"
[axes]
C = { start = 0.2, stop = 0.4, step = 0.05 }
ds_index = [1, 3]
)",
                                          "odd.toml");
  return sweep_rows(spec, ThreadBatchEvaluator(2));
}

}  // namespace

// Shards of the shipped specs, swept as a user would (2 threads, SIMD lanes),
// then every row re-run from its stored columns: Arnold (original, index
// switching, map zoning, scaling and their mixtures: table1.toml's shard),
// Logistic, Chebyshev, contraction and bouncing runs all come back bit for bit.
TEST(CliRunFrom, EveryRowOfShardsOfTheShippedSpecsIsReproducedBitForBit) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> shards{{"demo", "0/28"},    {"table1", "4/6"},
                                                                {"seed001", "0/32"}, {"seed002", "1/40"},
                                                                {"seed003", "0/6"},  {"fig6_paper_spread", "1/2"}};
  std::set<std::string> planners, variants;
  std::size_t rows = 0;
  for (const auto& [name, shard] : shards) {
    const std::string out = dir.file(name + ".h5");
    const auto r = run_chaosweep("sweep " + source_dir + "/experiments/" + name + ".toml -o " + out +
                                 " --threads 2 --shard " + shard + " -q --progress never");
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const std::vector<std::int64_t> ids = read_i64_column(out, "run_id");
    ASSERT_FALSE(ids.empty()) << name;
    for (std::int64_t id : ids) {
      const StoredRun stored = load_stored_run(out, id);
      const RowComparison cmp = compare_row(stored.row, {stored.tuple, SerialBatchEvaluator().evaluate(stored.tuple)});
      EXPECT_GT(cmp.compared.size(), 80u);
      for (const ColumnDifference& d : cmp.differences)
        ADD_FAILURE() << name << " run_id " << id << ": " << d.column << " stored " << d.stored << ", re-run "
                      << d.rerun;
      planners.insert(stored.row.text.at("planner"));
      variants.insert(stored.row.text.at("variant"));
      ++rows;
    }
    // The command itself, on the shard's last row.
    const auto c = run_chaosweep("run --from " + out + " --run-id " + std::to_string(ids.back()));
    EXPECT_EQ(c.exit_code, 0) << name << ": " << c.out << c.err;
    EXPECT_TRUE(has(c.out, "reproduced      yes: all ")) << c.out;
  }
  EXPECT_GE(rows, 100u);
  EXPECT_EQ(planners, (std::set<std::string>{"arnold", "logistic", "chebyshev", "contraction", "bouncing"}));
  for (const char* v : {"original", "index_switching", "map_zoning", "scaling"}) {
    bool seen = false;
    for (const std::string& s : variants) seen = seen || has(s, v);
    EXPECT_TRUE(seen) << "no " << v << " run among " << variants.size() << " variants";
  }
}

// The file alone decides the run: rows written without any spec on disk,
// with fixed settings far from the defaults, come back identical; a row
// whose stored dc was changed after the run is re-run with the stored dc,
// so its outputs differ, and each differing column is named.
TEST(CliRunFrom, UsesEveryStoredColumnAndNamesTheColumnsThatDiffer) {
  TempDir dir;
  std::vector<RunRow> rows = odd_rows();
  ASSERT_EQ(rows.size(), 10u);
  write_rows(dir.file("odd.h5"), rows);
  for (std::int64_t id : {0, 4, 9}) {
    const auto r = run_chaosweep("run --from " + dir.file("odd.h5") + " --run-id " + std::to_string(id));
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("reproduced      yes: all [0-9]+ stored columns bit-identical")))
        << r.out;
    EXPECT_TRUE(has(r.out, "14 x 11 m, sr 1.5 m, start (2.25, 3.5)")) << r.out;
  }
  // Run 4 is C = 0.3 (not 0.30000000000000004), ds_index 1.
  EXPECT_EQ(rows[4].tuple.params.C, 0.3);
  rows[4].tuple.params.dc = 0.6;  // as if the file said dc = 0.6 for outputs made at 0.8
  write_rows(dir.file("changed.h5"), rows);
  const auto r = run_chaosweep("run --from " + dir.file("changed.h5") + " --run-id 4");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(has(r.out, "reproduced      no: ")) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("\n  steps: stored [0-9]+, re-run [0-9]+\n"))) << r.out;
  EXPECT_TRUE(has(r.out, "\n  final_coverage: stored ")) << r.out;
  EXPECT_FALSE(has(r.out, "  dc:")) << r.out;  // the input is the stored one
  // --json: the row on stdout, the verdict on stderr; the exit status as without.
  const auto j = run_chaosweep("run --from " + dir.file("changed.h5") + " --run-id 4 --json");
  EXPECT_EQ(j.exit_code, 1);
  EXPECT_TRUE(has(j.out, "\"dc\": 0.6")) << j.out;
  EXPECT_TRUE(has(j.err, "reproduced      no: ")) << j.err;
}

TEST(CliRunFrom, BadInputIsNamedAndExits2) {
  TempDir dir;
  write_rows(dir.file("odd.h5"), odd_rows());
  const std::string odd = dir.file("odd.h5");
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases{
      {"run --from " + odd, "--from requires --run-id"},
      {"run --run-id 3", "--run-id requires --from"},
      {"run --from " + odd + " --run-id 10", "no run with run_id 10 (its 10 runs have run_ids 0 to 9)"},
      {"run --from " + odd + " --run-id -1", "--run-id: Value -1 not in range"},
      {"run --from " + odd + " --run-id 2 --ds-index 3", "--from re-runs the stored parameters: drop --ds-index"},
      {"run --from " + dir.file("missing.h5") + " --run-id 0", "--from: File does not exist"},
  };
  for (const Case& c : cases) {
    const auto r = run_chaosweep(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.out << r.err;
    EXPECT_TRUE(has(r.err, c.message)) << c.args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
  write_file(dir.file("text.h5"), "not hdf5\n");
  auto r = run_chaosweep("run --from " + dir.file("text.h5") + " --run-id 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "is not an HDF5 file")) << r.err;
  test::write_foreign_file(dir.file("foreign.h5"), "other-columns");
  r = run_chaosweep("run --from " + dir.file("foreign.h5") + " --run-id 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "no 'run_id' column")) << r.err;
  // A row whose environment file is gone since the sweep.
  write_file(dir.file("box.toml"), "obstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n");
  r = run_chaosweep("run --size 10 --sr 1 --env " + dir.file("box.toml") + " --start 1,1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  write_file(dir.file("env.toml"), "[fixed]\nsize = 10\nsr = 1\nstart = [1, 1]\nenv = \"" + dir.file("box.toml") +
                                       "\"\n[axes]\nA = [0.4, 0.5]\n");
  r = run_chaosweep("sweep " + dir.file("env.toml") + " -o " + dir.file("env.h5") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::filesystem::remove(dir.file("box.toml"));
  r = run_chaosweep("run --from " + dir.file("env.h5") + " --run-id 1");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(has(r.err, "env.h5: run_id 1: ") && has(r.err, "box.toml")) << r.err;
}

// A stored row is checked against the spec's ranges before it is rebuilt:
// a damaged or foreign file's value is refused naming its column, never
// converted (1e300 or NaN into an integer field is undefined behaviour).
TEST(CliRunFrom, AStoredValueOutOfItsRangeIsRefusedNamingTheColumn) {
  TempDir dir;
  write_rows(dir.file("odd.h5"), odd_rows());
  const StoredRow good = stored_row(read_all_columns(dir.file("odd.h5")), 2);
  EXPECT_EQ(double(run_spec_of(good).params.ds_index), good.numeric.at("ds_index"));
  struct Case {
    const char* column;
    double value;
    const char* message;
  };
  const Case cases[] = {
      {"ds_index", 1e300, "column ds_index = 1e+300 is out of range: must be "},
      {"ds_index", 2.5, "column ds_index = 2.5 is out of range: must be "},
      {"ds_index", std::nan(""), "column ds_index = nan is out of range: must be "},
      {"seed", -1, "column seed = -1 is out of range: must be "},
      {"sr", -std::numeric_limits<double>::infinity(), "column sr = -inf is out of range: must be "},
  };
  for (const Case& c : cases) {
    StoredRow bad = good;
    ASSERT_TRUE(bad.numeric.count(c.column)) << c.column;
    bad.numeric[c.column] = c.value;
    try {
      (void)run_spec_of(bad);
      ADD_FAILURE() << c.column << " = " << c.value << " was accepted";
    } catch (const SpecError& e) {
      EXPECT_TRUE(has(e.what(), c.message)) << e.what();
    }
  }
}

// A tuple as `table best` prints it, typed into `run`, gives the stored row:
// the demo's grid holds 0.3 and 0.35 themselves, and every table prints them
// in shortest round-trip form (CSV: the coverage time in full too).
TEST(CliRunFrom, ATuplePrintedByTableBestTypedIntoRunReproducesTheStoredRow) {
  TempDir dir;
  const std::string h5 = dir.file("demo.h5");
  auto r = run_chaosweep("sweep " + source_dir + "/experiments/demo.toml -o " + h5 + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_chaosweep("table best " + h5 + " --top 4 --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  ASSERT_EQ(line, "rank,A,B,C,median CT,min CT,ok,median PR");
  int checked = 0;
  while (std::getline(lines, line)) {
    std::vector<std::string> cell;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cell.push_back(c);
    ASSERT_EQ(cell.size(), 8u) << line;
    for (int k = 1; k <= 3; ++k)
      EXPECT_LE(cell[std::size_t(k)].size(), 4u) << "a grid value with float noise: " << line;
    // demo.toml's fixed settings, then the printed tuple.
    const auto run = run_chaosweep(
        "run --planner arnold --env empty --size 50 --sr 4 --ds-index 3 --start 0.5,0.5 "
        "--dc 0.9 --max-time 10000 --A " +
        cell[1] + " --B " + cell[2] + " --C " + cell[3] + " --json");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(has(run.out, "\"coverage_time\": " + cell[4] + ",")) << line << "\n" << run.out;
    ++checked;
  }
  EXPECT_EQ(checked, 4);
}

// Grids written differently hold the same decimals: the demo's axes (num
// ranges and a step of 0.05) against finer steps and a num range align on
// every run (before, float noise left 120 of the 280 aligned).
TEST(CliCompare, GridsOfDifferentStepsAlignOnTheirCommonDecimals) {
  TempDir dir;
  const std::string fixed = "[fixed]\nsize = 6\nsr = 2\nmax_time = 300\n[axes]\n";
  write_file(dir.file("coarse.toml"), fixed +
                                          "A = { start = 0.35, stop = 0.65, num = 7 }\n"
                                          "B = { start = 0.1, stop = 0.8, num = 8 }\n"
                                          "C = { start = 0.2, stop = 0.4, step = 0.05 }\n");
  write_file(dir.file("fine.toml"), fixed +
                                        "A = { start = 0.35, stop = 0.65, step = 0.01 }\n"
                                        "B = { start = 0.1, stop = 0.8, step = 0.1 }\n"
                                        "C = { start = 0.2, stop = 0.4, num = 5 }\n");
  for (const char* name : {"coarse", "fine"}) {
    const auto r = run_chaosweep("sweep " + dir.file(std::string(name) + ".toml") + " -o " +
                                 dir.file(std::string(name) + ".h5") + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto r = run_chaosweep("compare " + dir.file("coarse.h5") + " " + dir.file("fine.h5"));
  EXPECT_TRUE(
      has(r.out, "aligned on parameters (param_hash): 280 runs, 280 identical, 0 changed; 0 only in A, 960 only in B"))
      << r.out;
}
