// The command line, exercised as a user would: the built binary, its output
// and its exit status.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <algorithm>
#include <regex>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include "h5_store.hpp"
#include "result_columns.hpp"
#include "test_util.hpp"

using namespace chaosweep;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  const std::regex re("\"" + key + "\": ([-0-9.eE+]+|null)");
  if (!std::regex_search(json, m, re) || m[1] == "null") return NAN;
  return std::stod(m[1]);
}

const char* small_sweep = R"(
[sweep]
name = "cli-small"
[fixed]
size = 12
sr = 2
max_time = 2000
[axes]
A = [0.4, 0.5, 0.6]
B = [0.2, 0.3]
ds_index = [1, 2, 3]
)";

}  // namespace

TEST(CliRun, PapersRow1EndsOkWithCoverageTimeInThousandsOfSeconds) {
  const auto r = run_chaosweep("run --planner arnold --size 50 --sr 1 --ds-index 3 --start 0.5,0.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"status\": \"ok\""), std::string::npos) << r.out;
  const double ct = json_number(r.out, "coverage_time");
  EXPECT_GE(ct, 1000.0);
  EXPECT_LT(ct, 45000.0);
  EXPECT_DOUBLE_EQ(json_number(r.out, "t_opt"), 2250.0);
  EXPECT_DOUBLE_EQ(json_number(r.out, "pr"), ct / 2250.0);
  EXPECT_DOUBLE_EQ(json_number(r.out, "final_coverage"), 0.9);
  EXPECT_GT(json_number(r.out, "steps"), 0);
}

TEST(CliRun, PrintsAReadableResultWithoutJson) {
  const auto r = run_chaosweep("run --size 20 --sr 2 --A 0.5 --B 0.25 --C 0.25");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("status          ok"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("PR "), std::string::npos) << r.out;
}

TEST(CliRun, OutOfRangeFlagNamesTheFlagAndRangeAndExits2) {
  const auto r = run_chaosweep("run --sr 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--sr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[0.001, 10000]"), std::string::npos) << r.err;
  const auto d = run_chaosweep("run --ds-index 7");
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("--ds-index"), std::string::npos) << d.err;
  const auto s = run_chaosweep("run --start 3");
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.err.find("start must be an array of 2 numbers"), std::string::npos) << s.err;
}

TEST(CliRun, StartInsideAnObstacleIsInvalidAndExits2) {
  TempDir tmp;
  write_file(tmp.file("box.toml"), "obstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n");
  const auto r = run_chaosweep("run --size 10 --env " + tmp.file("box.toml") + " --start 5,5 --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("\"status\": \"invalid\""), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("inside obstacle"), std::string::npos) << r.err;
}

TEST(CliSweep, WritesOneRowPerRunIndependentOfThreads) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  const auto one = run_chaosweep("sweep " + tmp.file("s.toml") + " -o " + tmp.file("one.h5") + " --threads 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two = run_chaosweep("sweep " + tmp.file("s.toml") + " -o " + tmp.file("two.h5") + " --threads 2");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_NE(one.out.find("runs        18"), std::string::npos) << one.out;
  EXPECT_NE(one.out.find("median CT"), std::string::npos) << one.out;
  for (const char* col : {"coverage_time", "final_coverage", "final_x", "final_y", "t_end"}) {
    const auto a = read_f64_column(tmp.file("one.h5"), col), b = read_f64_column(tmp.file("two.h5"), col);
    ASSERT_EQ(a.size(), 18u);
    for (std::size_t i = 0; i < a.size(); ++i)
      EXPECT_TRUE(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i]))) << col << " row " << i;
  }
  EXPECT_EQ(read_text_column(tmp.file("one.h5"), "status"), read_text_column(tmp.file("two.h5"), "status"));
  EXPECT_EQ(read_attribute(tmp.file("one.h5"), "threads"), "1");
}

TEST(CliSweep, BadSpecExits2AndWritesNothing) {
  TempDir tmp;
  write_file(tmp.file("bad.toml"), "[axes]\nsr = [1, -4]\n");
  const auto r = run_chaosweep("sweep " + tmp.file("bad.toml") + " -o " + tmp.file("out.h5"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("axes.sr[1]"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.file("out.h5")));
  EXPECT_FALSE(std::filesystem::exists(tmp.file("out.h5.partial")));
}

TEST(CliSweep, EveryTable1RowRunsToOkWithThePapersParameters) {
  TempDir tmp;
  const auto r = run_chaosweep("sweep " + std::string(CHAOSWEEP_SOURCE_DIR) + "/experiments/table1.toml -o " +
                               tmp.file("t1.h5") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto labels = read_text_column(tmp.file("t1.h5"), "label");
  const auto status = read_text_column(tmp.file("t1.h5"), "status");
  ASSERT_EQ(labels.size(), 47u);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    EXPECT_EQ(labels[i], std::to_string(i + 1));
    EXPECT_EQ(status[i], "ok") << "Table 1 row " << labels[i];
  }
}

TEST(CliRun, TraceWritesTheTrajectoryAsCsv) {
  TempDir tmp;
  const auto r = run_chaosweep("run --size 20 --sr 1 --env five_squares --map-zoning 1 --c 1 --trace " +
                               tmp.file("trace.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = chaosweep::test::read_file(tmp.file("trace.csv"));
  EXPECT_EQ(csv.rfind("t,x,y,kind,ds_index\n0,6,2,start,3\n", 0), 0u) << csv.substr(0, 80);
  EXPECT_NE(csv.find(",arnold,"), std::string::npos);
  EXPECT_NE(csv.find(",transit,"), std::string::npos);
  const auto rows = std::count(csv.begin(), csv.end(), '\n');
  EXPECT_GT(rows, 1000);
}

// ------------------------------------------------------- store robustness

namespace {

// 1,200 runs of the demo's map: a few seconds in 100-run batches.
const char* long_sweep = R"(
[fixed]
size = 50
sr = 4
start = [0.5, 0.5]
max_time = 10000
[axes]
A = { start = 0.35, stop = 0.65, num = 20 }
B = { start = 0.1, stop = 0.8, num = 20 }
C = [0.2, 0.3, 0.4]
)";

// Rows equal in every column but wall time (which is no part of a run's result).
void expect_same_results(const std::string& a, const std::string& b) {
  for (const chaosweep::Column& c : chaosweep::result_columns()) {
    if (!c.deterministic) continue;
    if (c.type == chaosweep::Column::Type::f64) {
      const auto x = read_f64_column(a, c.name), y = read_f64_column(b, c.name);
      ASSERT_EQ(x.size(), y.size()) << c.name;
      for (std::size_t i = 0; i < x.size(); ++i)
        ASSERT_TRUE(x[i] == y[i] || (std::isnan(x[i]) && std::isnan(y[i]))) << c.name << " row " << i;
    } else if (c.type == chaosweep::Column::Type::i64) {
      ASSERT_EQ(read_i64_column(a, c.name), read_i64_column(b, c.name)) << c.name;
    } else {
      ASSERT_EQ(read_text_column(a, c.name), read_text_column(b, c.name)) << c.name;
    }
  }
}

// Waits until `partial` holds at least `rows` rows (read between the
// writer's batches) or the process has ended; false on timeout.
bool wait_for_rows(const std::string& partial, std::int64_t rows, int pid) {
  for (int i = 0; i < 6000; ++i) {
    if (std::filesystem::exists(partial)) {
      try {
        if (chaosweep::count_rows(partial) >= rows) return true;
      } catch (const std::exception&) {
        // the writer has the file open right now
      }
    }
    if (waitpid(pid, nullptr, WNOHANG) == pid) return false;
    usleep(10000);
  }
  return false;
}

}  // namespace

TEST(CliSweep, KillNineThenResumeGivesTheUninterruptedFile) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), long_sweep);
  const std::string args = tmp.file("s.toml") + " --threads 1 --batch 100 -q -o ";
  const int pid = chaosweep::test::start_chaosweep("sweep " + args + tmp.file("r.h5"));
  ASSERT_TRUE(wait_for_rows(tmp.file("r.h5.partial"), 200, pid)) << "the sweep wrote no batches";
  kill(pid, SIGKILL);  // right after a batch: the next write is a batch away
  EXPECT_EQ(chaosweep::test::wait_exit(pid), 128 + SIGKILL);
  EXPECT_FALSE(std::filesystem::exists(tmp.file("r.h5")));
  const auto again = run_chaosweep("sweep " + args + tmp.file("r.h5"));
  EXPECT_EQ(again.exit_code, 2);  // a partial file is never overwritten without --resume
  EXPECT_NE(again.err.find("--resume"), std::string::npos) << again.err;
  const auto resumed = run_chaosweep("sweep " + args + tmp.file("r.h5") + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const auto whole = run_chaosweep("sweep " + args + tmp.file("whole.h5"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  expect_same_results(tmp.file("r.h5"), tmp.file("whole.h5"));
  EXPECT_EQ(chaosweep::count_rows(tmp.file("r.h5")), 1200);
}

TEST(CliSweep, SigintStopsCleanlyAndResumeCompletes) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), long_sweep);
  const std::string args = tmp.file("s.toml") + " --threads 1 --batch 100 -q -o " + tmp.file("r.h5");
  const int pid = chaosweep::test::start_chaosweep("sweep " + args);
  ASSERT_TRUE(wait_for_rows(tmp.file("r.h5.partial"), 100, pid));
  kill(pid, SIGINT);
  EXPECT_EQ(chaosweep::test::wait_exit(pid), 130);
  const std::int64_t kept = chaosweep::count_rows(tmp.file("r.h5.partial"));
  EXPECT_GE(kept, 100);
  EXPECT_LT(kept, 1200);
  const auto resumed = run_chaosweep("sweep " + args + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(chaosweep::count_rows(tmp.file("r.h5")), 1200);
  const auto done = run_chaosweep("sweep " + args + " --resume");  // idempotent: nothing left to do
  EXPECT_EQ(done.exit_code, 0);
}

TEST(CliMerge, ShardsMergedEqualTheSingleMachineFile) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  std::string shards;
  for (int k = 0; k < 3; ++k) {
    const std::string out = tmp.file("shard" + std::to_string(k) + ".h5");
    const auto r = run_chaosweep("sweep " + tmp.file("s.toml") + " -q --shard " + std::to_string(k) + "/3 -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    shards += " " + out;
  }
  const auto merged = run_chaosweep("merge -o " + tmp.file("merged.h5") + shards);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  const auto whole = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("whole.h5"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  expect_same_results(tmp.file("merged.h5"), tmp.file("whole.h5"));
  EXPECT_EQ(read_attribute(tmp.file("merged.h5"), "spec"), read_attribute(tmp.file("whole.h5"), "spec"));
}

TEST(CliMerge, NamesTheMissingShardAndWritesNothing) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  for (int k : {0, 2}) {
    const auto r = run_chaosweep("sweep " + tmp.file("s.toml") + " -q --shard " + std::to_string(k) + "/3 -o " +
                                 tmp.file("shard" + std::to_string(k) + ".h5"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto merged =
      run_chaosweep("merge -o " + tmp.file("m.h5") + " " + tmp.file("shard0.h5") + " " + tmp.file("shard2.h5"));
  EXPECT_EQ(merged.exit_code, 1);
  EXPECT_NE(merged.out.find("re-run shards 1 of 3"), std::string::npos) << merged.out;
  EXPECT_NE(merged.out.find("missing 6 runs"), std::string::npos) << merged.out;
  EXPECT_FALSE(std::filesystem::exists(tmp.file("m.h5")));
}

TEST(CliSweep, BadShardIsNamed) {
  const auto r = run_chaosweep("sweep " + std::string(CHAOSWEEP_SOURCE_DIR) + "/experiments/demo.toml -o /tmp/x.h5 --shard 3/3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--shard"), std::string::npos) << r.err;
}

namespace {
// Overwrites one float cell of /runs in place (to fake a changed result).
void poke_f64(const std::string& path, const char* column, hsize_t row, double value) {
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t dset = H5Dopen2(file, "/runs", H5P_DEFAULT);
  hid_t mem = H5Tcreate(H5T_COMPOUND, sizeof(double));
  H5Tinsert(mem, column, 0, H5T_NATIVE_DOUBLE);
  hid_t fspace = H5Dget_space(dset);
  const hsize_t count = 1;
  H5Sselect_hyperslab(fspace, H5S_SELECT_SET, &row, nullptr, &count, nullptr);
  hid_t mspace = H5Screate_simple(1, &count, nullptr);
  H5Dwrite(dset, mem, mspace, fspace, H5P_DEFAULT, &value);
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Tclose(mem);
  H5Dclose(dset);
  H5Fclose(file);
}
}  // namespace

TEST(CliCompare, ExitsZeroOnIdenticalAndOneOnAChangeBeyondTolerance) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  for (const char* name : {"a.h5", "b.h5"}) {
    const auto r = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file(name));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto same = run_chaosweep("compare " + tmp.file("a.h5") + " " + tmp.file("b.h5"));
  EXPECT_EQ(same.exit_code, 0) << same.out;
  EXPECT_NE(same.out.find("18 identical, 0 changed"), std::string::npos) << same.out;

  const double t_end = read_f64_column(tmp.file("b.h5"), "t_end")[3];
  poke_f64(tmp.file("b.h5"), "t_end", 3, t_end * (1 + 1e-9));
  const auto changed = run_chaosweep("compare " + tmp.file("a.h5") + " " + tmp.file("b.h5"));
  EXPECT_EQ(changed.exit_code, 1);
  EXPECT_NE(changed.out.find("run_id 3: t_end"), std::string::npos) << changed.out;
  EXPECT_NE(changed.out.find("1 changed"), std::string::npos) << changed.out;
  const auto tolerated = run_chaosweep("compare " + tmp.file("a.h5") + " " + tmp.file("b.h5") + " --rtol 1e-8");
  EXPECT_EQ(tolerated.exit_code, 0) << tolerated.out;
}

TEST(CliPlan, ShowsRunsAxesAndAWorkBound) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  const auto r = run_chaosweep("plan " + tmp.file("s.toml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("runs        18  (3 x 2 x 3)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("A: 3 values: 0.4, 0.5, 0.6"), std::string::npos) << r.out;
  // 18 runs, each at most 2000 s / 0.1 s steps.
  EXPECT_NE(r.out.find("at most 3.6e+05 integration steps"), std::string::npos) << r.out;
  const auto bad = run_chaosweep("plan " + std::string(CHAOSWEEP_SOURCE_DIR) + "/README.md");
  EXPECT_EQ(bad.exit_code, 2);
}
