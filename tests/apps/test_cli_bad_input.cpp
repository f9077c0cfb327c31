// Bad input on the command line (issue 11, docs/inputs.md): flags, specs and
// environments given to run/sweep, and result files given to merge, compare,
// table and figure. Each test pins the exit status, that the message names
// the flag, file or field, and that no output file appears.
#include <gtest/gtest.h>

#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "tests/support/test_util.hpp"

using chaosweep::test::has;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

namespace fs = std::filesystem;

// No output and no partial output of `out`.
void expect_nothing_written(const std::string& out) {
  EXPECT_FALSE(fs::exists(out)) << out;
  EXPECT_FALSE(fs::exists(out + ".partial")) << out;
}

const char* bad_input_sweep = R"(
[sweep]
name = "bad-input"
[fixed]
size = 12
sr = 2
max_time = 500
[axes]
A = [0.4, 0.5, 0.6]
ds_index = [1, 2]
)";

}  // namespace

// ------------------------------------------------------------------ flags

TEST(CliRun, WrongTypeFlagValuesNameTheFlagAndExit2) {
  auto r = run_chaosweep("run --sr abc");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "--sr: 'abc' is not a number")) << r.err;
  r = run_chaosweep("run --size 10,abc");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "--size") && has(r.err, "'10,abc' is not a number (or X,Y)")) << r.err;
  r = run_chaosweep("run --planner foo");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "--planner: planner = \"foo\" is not allowed: must be one of arnold, logistic")) << r.err;
  r = run_chaosweep("run --start 1,2,3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "--start") && has(r.err, "2 numbers")) << r.err;
  r = run_chaosweep("run --boundary");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "--boundary")) << r.err;
  r = run_chaosweep("run --bogus 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "--bogus")) << r.err;
}

TEST(CliRun, NanInfAndOutOfRangeFlagValuesNameTheFlagAndTheRangeAndExit2) {
  struct Case {
    const char* args;
    const char* message;
  };
  for (const Case& c :
       {Case{"--sr nan", "--sr: sr = nan is out of range: must be a number in [0.001, 10000]"},
        Case{"--A inf", "--A: A = inf is out of range: must be a number in [-1000, 1000]"},
        Case{"--B -inf", "--B: B = -inf is out of range: must be a number in [-1000, 1000]"},
        Case{"--dc 1.5", "--dc: dc = 1.5 is out of range: must be a number in [1e-06, 1]"},
        Case{"--ds-index 2.5", "--ds-index: ds_index = 2.5 is out of range: must be an integer in [1, 3]"},
        Case{"--niter -1", "--niter: niter = -1 is out of range: must be an integer in [1, "},
        Case{"--size 0", "--size: size_x = 0 is out of range: must be a number in [0.001, 1e+06]"}}) {
    const auto r = run_chaosweep(std::string("run ") + c.args + " --json");
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_TRUE(has(r.err, c.message)) << c.args << ": " << r.err;
    EXPECT_EQ(r.out, "") << c.args;  // no result printed
  }
}

TEST(CliSweep, OutOfRangeAndWrongTypeFlagsAreNamedAndNothingIsWritten) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), bad_input_sweep);
  const std::string base = "sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("out.h5") + " ";
  struct Case {
    const char* flags;
    const char* message;
  };
  for (const Case& c : {Case{"--threads -1", "--threads: Value -1 not in range"}, Case{"--threads abc", "--threads"},
                        Case{"--batch 0", "--batch: Value 0 not in range"},
                        Case{"--progress sometimes", "--progress: sometimes not in {auto,always,never}"},
                        Case{"--shard 2/1", "--shard: index 2 of 1 is out of range: need 0 <= K < N"},
                        Case{"--shard a/b", "--shard: 'a/b' is not K/N"}, Case{"--bogus", "--bogus"}}) {
    const auto r = run_chaosweep(base + c.flags);
    EXPECT_EQ(r.exit_code, 2) << c.flags;
    EXPECT_TRUE(has(r.err, c.message)) << c.flags << ": " << r.err;
    expect_nothing_written(tmp.file("out.h5"));
  }
  const auto no_out = run_chaosweep("sweep " + tmp.file("s.toml"));
  EXPECT_EQ(no_out.exit_code, 2);
  EXPECT_TRUE(has(no_out.err, "--output is required")) << no_out.err;
  const auto no_spec = run_chaosweep("sweep " + tmp.file("nope.toml") + " -o " + tmp.file("out.h5"));
  EXPECT_EQ(no_spec.exit_code, 2);
  EXPECT_TRUE(has(no_spec.err, "nope.toml")) << no_spec.err;
  expect_nothing_written(tmp.file("out.h5"));
}

// ------------------------------------------------------------- sweep specs

TEST(CliSweep, EachKindOfBadSpecIsNamedExits2AndWritesNothing) {
  TempDir tmp;
  struct Case {
    const char* spec;
    const char* message;
  };
  for (const Case& c :
       {Case{"[fixed]\nsr = 1\nA = = 2\n", "bad.toml: Error while parsing value"},
        Case{"[fixed]\nfoo = 1\n", "bad.toml: fixed.foo: unknown key 'foo' (known: "},
        Case{"[fixed]\nA = \"big\"\n", "bad.toml: fixed.A: A must be a number"},
        Case{"[fixed]\nA = nan\n", "bad.toml: fixed.A: A = nan is out of range: must be a number in [-1000, 1000]"},
        Case{"[axes]\nsr = [1, inf]\n", "bad.toml: axes.sr[1]: sr = inf is out of range"},
        Case{"[axes]\nA = []\n", "bad.toml: axes.A: is empty"},
        Case{"[axes]\nfoo = [1]\n", "bad.toml: axes.foo[0]: unknown key 'foo'"},
        Case{"[sweep]\nextends = \"no_such_parent.toml\"\n",
             "no_such_parent.toml: cannot open the spec named by sweep.extends"}}) {
    write_file(tmp.file("bad.toml"), c.spec);
    const auto r = run_chaosweep("sweep " + tmp.file("bad.toml") + " -q -o " + tmp.file("out.h5"));
    EXPECT_EQ(r.exit_code, 2) << c.spec;
    EXPECT_TRUE(has(r.err, c.message)) << c.spec << ": " << r.err;
    expect_nothing_written(tmp.file("out.h5"));
    const auto plan = run_chaosweep("plan " + tmp.file("bad.toml"));  // plan refuses it alike
    EXPECT_EQ(plan.exit_code, 2) << c.spec;
    EXPECT_TRUE(has(plan.err, c.message)) << c.spec << ": " << plan.err;
  }
  // The line of a TOML error.
  write_file(tmp.file("bad.toml"), "[fixed]\nsr = 1\nA = = 2\n");
  EXPECT_TRUE(has(run_chaosweep("plan " + tmp.file("bad.toml")).err, "line 3"));
}

TEST(CliSweep, AnEnvironmentThatDoesNotExistIsNamedAndNothingIsWritten) {
  TempDir tmp;
  for (const std::string& env : {std::string("no_such_env"), tmp.file("missing/env.toml")}) {
    std::string spec = bad_input_sweep;
    spec.insert(spec.find("size = 12"), "env = \"" + env + "\"\n");
    write_file(tmp.file("s.toml"), spec);
    const auto r = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("out.h5"));
    EXPECT_EQ(r.exit_code, 2) << env;
    EXPECT_TRUE(has(r.err, "fixed: environment '" + env + "' not found")) << r.err;
    expect_nothing_written(tmp.file("out.h5"));
  }
  // On an axis: the axis and the position are named.
  std::string spec = bad_input_sweep;
  spec += "env = [\"empty\", \"no_such_env\"]\n";
  write_file(tmp.file("s.toml"), spec);
  const auto r = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("out.h5"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "env[1]: environment 'no_such_env' not found")) << r.err;
  expect_nothing_written(tmp.file("out.h5"));
}

// ------------------------------------------------------- environment files

TEST(CliSweep, ABadEnvironmentFileIsNamedExits2AndWritesNothing) {
  TempDir tmp;
  struct Case {
    const char* env;
    const char* message;
  };
  for (const Case& c : {
           Case{"obstacles = [\n", "env.toml: Error while parsing array"},
           Case{"colour = 1\n", "env.toml: unknown key 'colour' (allowed: name, description"},
           Case{"size = \"big\"\n", "env.toml: 'size' must be a number or [x, y]"},
           Case{"obstacles = [{ x = nan, y = 0.1, w = 0.1, h = 0.1 }]\n",
                "'obstacles[0].x' = nan must be a finite number"},
           Case{"obstacles = [{ x = 0.1, y = 0.1, w = 0.1, h = 0.1 }, { x = 0.8, y = 0.1, w = 0.4, h = 0.1 }]\n",
                "env.toml: obstacles[1] spans [9.6, 14.4] x [1.2, 2.4] m: it reaches outside the map [0, 12] x [0, 12] "
                "m"},
           Case{"obstacles = [{ x = 2, y = 2, w = 0.5, h = 0.5 }]\n",
                "obstacles[0] spans [24, 30] x [24, 30] m: it lies outside the map"},
           Case{"start = [0.5, 0.5]\nobstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n",
                "env.toml: 'start' = (6, 6) m lies inside obstacles[0]"},
           Case{"start = [1.5, 0.5]\n", "env.toml: 'start' = (18, 6) m is outside the map [0, 12] x [0, 12] m"},
       }) {
    write_file(tmp.file("env.toml"), c.env);
    std::string spec = bad_input_sweep;
    spec.insert(spec.find("size = 12"), "env = \"" + tmp.file("env.toml") + "\"\n");
    write_file(tmp.file("s.toml"), spec);
    const auto r = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("out.h5"));
    EXPECT_EQ(r.exit_code, 2) << c.env;
    EXPECT_TRUE(has(r.err, c.message)) << c.env << ": " << r.err;
    expect_nothing_written(tmp.file("out.h5"));
    const auto run = run_chaosweep("run --size 12 --env " + tmp.file("env.toml") + " --json");
    EXPECT_EQ(run.exit_code, 2) << c.env;
    EXPECT_TRUE(has(run.err, c.message)) << c.env << ": " << run.err;
  }
}

TEST(CliRun, StartOutsideTheMapIsInvalidNamingTheMapAndExits2) {
  const auto r = run_chaosweep("run --size 10 --start 60,5 --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.out, "\"status\": \"invalid\"")) << r.out;
  EXPECT_TRUE(has(r.err, "start (60, 5) is outside the map [0, 10] x [0, 10]")) << r.err;
}

TEST(CliRun, OverlappingObstaclesAreOneObstacleTheirUnion) {
  TempDir tmp;
  write_file(tmp.file("overlap.toml"),
             "obstacles = [{ x = 0.2, y = 0.2, w = 0.4, h = 0.4 }, { x = 0.4, y = 0.4, w = 0.4, h = 0.4 }]\n");
  const auto r = run_chaosweep("run --size 10 --max-time 50 --env " + tmp.file("overlap.toml") + " --json");
  EXPECT_NE(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.out, "\"free_cells\": 72")) << r.out;  // 100 cells minus the union's 16 + 16 - 4
}

// ------------------------------------------------------------ result files

// Outside the anonymous namespace: the test classes derive from it (GCC
// warns of that in a unity batch, -Wsubobject-linkage).

// One set of result files for every test below: a whole sweep, its two
// shards, a shard of another spec, and broken or foreign files.
class BadResultFiles : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    write_file(file("s.toml"), bad_input_sweep);
    std::string other = bad_input_sweep;
    other.replace(other.find("max_time = 500"), 14, "max_time = 600");
    write_file(file("other.toml"), other);
    const std::string sweep = "sweep " + file("s.toml") + " -q -o ";
    ok_ = run_chaosweep(sweep + file("good.h5")).exit_code == 0 &&
          run_chaosweep(sweep + file("shard0.h5") + " --shard 0/2").exit_code == 0 &&
          run_chaosweep(sweep + file("shard1.h5") + " --shard 1/2").exit_code == 0 &&
          run_chaosweep("sweep " + file("other.toml") + " -q --shard 1/2 -o " + file("other_shard1.h5")).exit_code == 0;
    if (!ok_) return;
    const std::string bytes = chaosweep::test::read_file(file("good.h5"));
    write_file(file("truncated.h5"), bytes.substr(0, bytes.size() / 2));
    write_file(file("text.h5"), "run_id,status\n0,ok\n");
    chaosweep::test::write_foreign_file(file("no-runs.h5"), "no-runs");
    chaosweep::test::write_foreign_file(file("other-columns.h5"), "other-columns");
    chaosweep::test::write_foreign_file(file("not-compound.h5"), "not-compound");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  void SetUp() override { ASSERT_TRUE(ok_) << "could not make the result files"; }
  static std::string file(const std::string& name) { return dir_->file(name); }

  struct Bad {
    std::string name, why;  // file, and what the message says is wrong with it
  };
  // What every reader says about each bad file (the missing file is refused
  // by the command line's own check).
  static std::vector<Bad> bad_files() {
    return {{"truncated.h5", "truncated.h5 is truncated or damaged: HDF5 cannot open it"},
            {"text.h5", "text.h5 is not an HDF5 file (not a chaosweep result file)"},
            {"no-runs.h5", "no-runs.h5 has no /runs dataset (not a chaosweep result file)"},
            {"not-compound.h5", "not-compound.h5: /runs is not a table of columns (not a chaosweep result file)"},
            {"other-columns.h5", "other-columns.h5"},
            {"missing.h5", "File does not exist: " + file("missing.h5")}};
  }
  // Exit 2, the file named with the reason, no HDF5 error stack.
  static void expect_refused(const chaosweep::test::CommandResult& r, const Bad& b, const std::string& what) {
    EXPECT_EQ(r.exit_code, 2) << what << " " << b.name << ": " << r.err;
    EXPECT_TRUE(has(r.err, b.why)) << what << " " << b.name << ": " << r.err;
    EXPECT_TRUE(has(r.err, file(b.name))) << what << " " << b.name << ": " << r.err;
    EXPECT_FALSE(has(r.err, "HDF5-DIAG")) << what << " " << b.name << ": " << r.err;
  }

  static TempDir* dir_;
  static bool ok_;
};
TempDir* BadResultFiles::dir_ = nullptr;
bool BadResultFiles::ok_ = false;

TEST_F(BadResultFiles, MergeNamesABrokenOrForeignShardAndWritesNothing) {
  for (const Bad& b : bad_files()) {
    for (const bool first : {true, false}) {
      const std::string inputs =
          first ? file(b.name) + " " + file("shard1.h5") : file("shard0.h5") + " " + file(b.name);
      const auto r = run_chaosweep("merge -o " + file("merged.h5") + " " + inputs);
      Bad want = b;
      if (b.name == "no-runs.h5" || b.name == "not-compound.h5" || b.name == "other-columns.h5")
        want.why = b.name + " has no attribute 'spec_hash' (not a chaosweep result file?)";
      expect_refused(r, want, "merge");
      expect_nothing_written(file("merged.h5"));
    }
  }
}

TEST_F(BadResultFiles, MergeRefusesShardsOfDifferentSpecsAndWritesNothing) {
  const auto r =
      run_chaosweep("merge -o " + file("merged.h5") + " " + file("shard0.h5") + " " + file("other_shard1.h5"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(
      r.err, file("other_shard1.h5") + " comes from another spec than " + file("shard0.h5") + " (spec_hash differs)"))
      << r.err;
  expect_nothing_written(file("merged.h5"));
  // A whole-sweep file and a shard of the same spec: different shard counts.
  const auto n = run_chaosweep("merge -o " + file("merged.h5") + " " + file("shard0.h5") + " " + file("good.h5"));
  EXPECT_EQ(n.exit_code, 2);
  EXPECT_TRUE(has(n.err, file("good.h5") + " is shard 0/1 but " + file("shard0.h5") + " has 2 shards")) << n.err;
  expect_nothing_written(file("merged.h5"));
}

TEST_F(BadResultFiles, MergeRefusesTheSameShardTwiceNamingBothFiles) {
  const auto twice = run_chaosweep("merge -o " + file("merged.h5") + " " + file("shard0.h5") + " " + file("shard1.h5") +
                                   " " + file("shard0.h5"));
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_TRUE(has(twice.err, file("shard0.h5") + " is given twice")) << twice.err;
  expect_nothing_written(file("merged.h5"));
  fs::copy_file(file("shard0.h5"), file("copy_of_shard0.h5"), fs::copy_options::overwrite_existing);
  const auto copy = run_chaosweep("merge -o " + file("merged.h5") + " " + file("shard0.h5") + " " + file("shard1.h5") +
                                  " " + file("copy_of_shard0.h5"));
  EXPECT_EQ(copy.exit_code, 2);
  EXPECT_TRUE(has(copy.err, file("copy_of_shard0.h5") + " and " + file("shard0.h5") + " are both shard 0/2"))
      << copy.err;
  expect_nothing_written(file("merged.h5"));
  // The good pair merges (the files above were not at fault).
  const auto ok = run_chaosweep("merge -o " + file("merged.h5") + " " + file("shard0.h5") + " " + file("shard1.h5"));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  fs::remove(file("merged.h5"));
}

TEST_F(BadResultFiles, CompareNamesABrokenOrForeignFileAndExits2) {
  for (const Bad& b : bad_files()) {
    for (const bool first : {true, false}) {
      const std::string args = first ? file(b.name) + " " + file("good.h5") : file("good.h5") + " " + file(b.name);
      const auto r = run_chaosweep("compare " + args);
      Bad want = b;
      if (b.name == "other-columns.h5")
        want.why = "other-columns.h5 has no 'run_id' column: not a chaosweep result file";
      expect_refused(r, want, "compare");
      EXPECT_EQ(r.out, "") << b.name;
    }
  }
}

TEST_F(BadResultFiles, TableNamesABrokenOrForeignFileAndWritesNothing) {
  for (const Bad& b : bad_files()) {
    const auto r = run_chaosweep("table summary " + file("good.h5") + " " + file(b.name) + " -o " + file("table.md"));
    Bad want = b;
    if (b.name == "other-columns.h5")
      want.why = "other-columns.h5: /runs has no 'run_id' column (not a chaosweep result file)";
    expect_refused(r, want, "table");
    EXPECT_FALSE(fs::exists(file("table.md"))) << b.name;
    const auto stdout_table = run_chaosweep("table best " + file(b.name));
    expect_refused(stdout_table, want, "table (stdout)");
    EXPECT_EQ(stdout_table.out, "") << b.name;
  }
}

TEST_F(BadResultFiles, FigureNamesABrokenOrForeignFileAndWritesNothing) {
  for (const Bad& b : bad_files()) {
    const auto r = run_chaosweep("figure fig6a " + file(b.name) + " -o " + file("fig.png"));
    Bad want = b;
    if (b.name == "other-columns.h5")
      want.why = "other-columns.h5: /runs has no 'run_id' column (not a chaosweep result file)";
    expect_refused(r, want, "figure");
    EXPECT_FALSE(fs::exists(file("fig.png"))) << b.name;
    EXPECT_FALSE(fs::exists(file("fig.png.csv")) || fs::exists(file("fig.csv"))) << b.name;
  }
}

TEST_F(BadResultFiles, MergeRefusesAMergedFileAsAShardAndWritesNothing) {
  const auto first =
      run_chaosweep("merge -o " + file("merged_once.h5") + " " + file("shard0.h5") + " " + file("shard1.h5"));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto again =
      run_chaosweep("merge -o " + file("merged.h5") + " " + file("merged_once.h5") + " " + file("shard1.h5"));
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_TRUE(
      has(again.err, file("merged_once.h5") + ": attribute 'shard' is 'merged from 2 files of 2 shards', not K/N"))
      << again.err;
  expect_nothing_written(file("merged.h5"));
  fs::remove(file("merged_once.h5"));
}
