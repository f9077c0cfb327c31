// The command line, exercised as a user would: the built binary, its output
// and its exit status.
#include <hdf5.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include "engine/rows/result_columns.hpp"
#include "engine/store/h5_store.hpp"
#include "tests/support/sanitizers.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::wait_for_rows;
using chaosweep::test::write_file;

namespace {

double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  const std::regex re("\"" + key + "\": ([-0-9.eE+]+|null)");
  if (!std::regex_search(json, m, re) || m[1] == "null") return NAN;
  return std::stod(m[1]);
}

// Cheap runs (a 6 m map, SR 2 m): about two thirds reach 90% in well under
// a minute of robot time, the rest time out; a_values x b_values runs.
std::string cheap_sweep(int a_values, int b_values) {
  return "[fixed]\nsize = 6\nsr = 2\n[axes]\nA = { start = 0.3, stop = 0.7, num = " + std::to_string(a_values) +
         " }\nB = { start = 0.1, stop = 0.8, num = " + std::to_string(b_values) + " }\n";
}

const std::string small_sweep = chaosweep::test::small_spec_18_runs("cli-small");

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
  const auto r =
      run_chaosweep("run --size 20 --sr 1 --env five_squares --map-zoning 1 --c 1 --trace " + tmp.file("trace.csv"));
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

// 24,000 cheap runs: about half a second on one thread, long enough to
// interrupt between its batches (12,000 took 0.28 s once rows were written
// behind the runs, and a kill then came after the sweep had finished).
const std::string long_sweep = cheap_sweep(24, 1000);
constexpr std::int64_t long_sweep_runs = 24000;

// Rows equal in every column but wall time (which is no part of a run's
// result). Integers are exact as doubles (< 2^53).
void expect_same_results(const std::string& a, const std::string& b) {
  const chaosweep::StoredColumns x = chaosweep::read_all_columns(a), y = chaosweep::read_all_columns(b);
  ASSERT_EQ(x.rows, y.rows);
  const auto deterministic = [](const std::string& name) {
    const chaosweep::Column* c = chaosweep::find_column(name);
    return c && c->deterministic;
  };
  ASSERT_EQ(x.numeric.size(), y.numeric.size());
  for (std::size_t k = 0; k < x.numeric.size(); ++k) {
    const auto& [name, u] = x.numeric[k];
    ASSERT_EQ(name, y.numeric[k].first);
    if (!deterministic(name)) continue;
    const auto& v = y.numeric[k].second;
    for (std::size_t i = 0; i < u.size(); ++i)
      ASSERT_TRUE(u[i] == v[i] || (std::isnan(u[i]) && std::isnan(v[i]))) << name << " row " << i;
  }
  ASSERT_EQ(x.text.size(), y.text.size());
  for (std::size_t k = 0; k < x.text.size(); ++k)
    if (deterministic(x.text[k].first)) {
      ASSERT_EQ(x.text[k].second, y.text[k].second) << x.text[k].first;
    }
}

}  // namespace

TEST(CliSweep, KillNineThenResumeGivesTheUninterruptedFile) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), long_sweep);
  const std::string args = tmp.file("s.toml") + " --threads 1 --batch 1000 -q -o ";
  const int pid = chaosweep::test::start_chaosweep("sweep " + args + tmp.file("r.h5"));
  ASSERT_TRUE(wait_for_rows(tmp.file("r.h5.partial"), 2000, pid)) << "the sweep wrote no batches";
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
  EXPECT_EQ(chaosweep::count_rows(tmp.file("r.h5")), long_sweep_runs);
}

namespace {
// `sig` mid-sweep: the runs in flight finish and are written, the exit code is
// 128 + sig, and --resume completes the file (and then has nothing to do).
void expect_signal_stops_cleanly_and_resume_completes(int sig) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), long_sweep);
  const std::string args = tmp.file("s.toml") + " --threads 1 --batch 1000 -q -o " + tmp.file("r.h5");
  const int pid = chaosweep::test::start_chaosweep("sweep " + args);
  ASSERT_TRUE(wait_for_rows(tmp.file("r.h5.partial"), 1000, pid));
  kill(pid, sig);
  EXPECT_EQ(chaosweep::test::wait_exit(pid), 128 + sig);
  const std::int64_t kept = chaosweep::count_rows(tmp.file("r.h5.partial"));
  EXPECT_GE(kept, 1000);
  EXPECT_LT(kept, long_sweep_runs);
  EXPECT_FALSE(std::filesystem::exists(tmp.file("r.h5.lock")));
  const auto resumed = run_chaosweep("sweep " + args + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(chaosweep::count_rows(tmp.file("r.h5")), long_sweep_runs);
  const auto done = run_chaosweep("sweep " + args + " --resume");  // idempotent: nothing left to do
  EXPECT_EQ(done.exit_code, 0);
}
}  // namespace

TEST(CliSweep, SigintStopsCleanlyAndResumeCompletes) { expect_signal_stops_cleanly_and_resume_completes(SIGINT); }

TEST(CliSweep, SigtermStopsCleanlyAndResumeCompletes) { expect_signal_stops_cleanly_and_resume_completes(SIGTERM); }

TEST(CliSweep, ResumeIsRefusedWhenAnEnvironmentFileChangedNamingIt) {
  // The rows before the interruption were made on env1.toml as it was; the
  // rest must not be made on an edited copy under the same name.
  ASSERT_EQ(long_sweep.rfind("[fixed]\n", 0), 0u);
  TempDir tmp;
  const std::string box = "obstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n";
  write_file(tmp.file("env1.toml"), box);
  write_file(tmp.file("s.toml"), "[fixed]\nenv = \"" + tmp.file("env1.toml") + "\"\n" + long_sweep.substr(8));
  const std::string args = tmp.file("s.toml") + " --threads 1 --batch 1000 -q -o " + tmp.file("r.h5");
  const int pid = chaosweep::test::start_chaosweep("sweep " + args);
  ASSERT_TRUE(wait_for_rows(tmp.file("r.h5.partial"), 1000, pid));
  kill(pid, SIGINT);
  ASSERT_EQ(chaosweep::test::wait_exit(pid), 128 + SIGINT);
  const std::int64_t kept = chaosweep::count_rows(tmp.file("r.h5.partial"));
  ASSERT_LT(kept, long_sweep_runs);
  // Provenance names every file read, with its content hash.
  const std::string files = chaosweep::read_attribute(tmp.file("r.h5.partial"), "input_files");
  EXPECT_NE(files.find("spec\t"), std::string::npos) << files;
  EXPECT_NE(files.find("\t" + tmp.file("s.toml") + "\n"), std::string::npos) << files;
  EXPECT_NE(files.find("env\t"), std::string::npos) << files;
  EXPECT_NE(files.find("\t" + tmp.file("env1.toml") + "\n"), std::string::npos) << files;
  write_file(tmp.file("env1.toml"), "obstacles = [{ x = 0.4, y = 0.4, w = 0.3, h = 0.2 }]\n");
  const auto refused = run_chaosweep("sweep " + args + " --resume");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find(tmp.file("r.h5.partial") + " was made with other input files: " + tmp.file("env1.toml") +
                             " changed (environment '" + tmp.file("env1.toml") + "')"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(chaosweep::count_rows(tmp.file("r.h5.partial")), kept);  // untouched
  // The map as it was: the resume completes and equals an uninterrupted sweep.
  write_file(tmp.file("env1.toml"), box);
  const auto resumed = run_chaosweep("sweep " + args + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const auto whole = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("whole.h5"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  expect_same_results(tmp.file("r.h5"), tmp.file("whole.h5"));
  // A complete file checks its inputs too.
  write_file(tmp.file("env1.toml"), "obstacles = [{ x = 0.1, y = 0.4, w = 0.3, h = 0.2 }]\n");
  const auto done = run_chaosweep("sweep " + args + " --resume");
  EXPECT_EQ(done.exit_code, 2) << done.err;
  EXPECT_NE(done.err.find(tmp.file("r.h5") + " was made with other input files"), std::string::npos) << done.err;
}

TEST(CliSweep, SecondSweepOnTheSameOutputIsRefused) {
  TempDir tmp;
  // Twice long_sweep: the first sweep must outlast both refused
  // attempts (each waits out OutputLock's retries), and long_sweep alone
  // ended before the second on an idle machine.
  const std::string spec = cheap_sweep(24, 2000);
  constexpr std::int64_t spec_runs = 48000;
  write_file(tmp.file("s.toml"), spec);
  const std::string args = tmp.file("s.toml") + " --threads 1 --batch 1000 -q -o " + tmp.file("r.h5");
  const int pid = chaosweep::test::start_chaosweep("sweep " + args);
  ASSERT_TRUE(wait_for_rows(tmp.file("r.h5.partial"), 1000, pid));
  for (const char* extra : {" --resume", " --force"}) {
    const auto second = run_chaosweep("sweep " + args + extra);
    EXPECT_EQ(second.exit_code, 2) << extra;
    EXPECT_NE(second.err.find("is being written by process " + std::to_string(pid)), std::string::npos) << second.err;
  }
  EXPECT_EQ(chaosweep::test::wait_exit(pid), 0);  // the first sweep never noticed
  EXPECT_EQ(chaosweep::count_rows(tmp.file("r.h5")), spec_runs);
  EXPECT_FALSE(std::filesystem::exists(tmp.file("r.h5.lock")));  // removed by its holder
  const auto whole = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("whole.h5"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  expect_same_results(tmp.file("r.h5"), tmp.file("whole.h5"));
}

TEST(CliSweep, FileSizeLimitStopsWithAResumableFile) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), long_sweep);
  const std::string args = tmp.file("s.toml") + " --threads 1 --batch 100 -q -o " + tmp.file("r.h5");
  // First learn what the empty file and one batch take: a 200 kB limit stops
  // before the first batch and says both.
  const auto probe = run_chaosweep("sweep " + args, "prlimit --fsize=200000");
  ASSERT_EQ(probe.exit_code, 3) << probe.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(probe.err, m, std::regex(R"(the file has (\d+), the next batch needs up to (\d+))")))
      << probe.err;
  EXPECT_NE(probe.err.find("ulimit -f"), std::string::npos) << probe.err;
  EXPECT_NE(probe.err.find("--resume"), std::string::npos) << probe.err;
  // Room for the first batch and a few more: the sweep stops between batches.
  const long limit = std::stol(m[1]) + std::stol(m[2]) + 40000;
  const auto r = run_chaosweep("sweep " + args + " --force", "prlimit --fsize=" + std::to_string(limit));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("make room, then continue with --resume"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.file("r.h5")));
  const std::int64_t kept = chaosweep::count_rows(tmp.file("r.h5.partial"));
  EXPECT_GE(kept, 100);
  EXPECT_LT(kept, long_sweep_runs);
  EXPECT_EQ(kept % 100, 0);
  const auto resumed = run_chaosweep("sweep " + args + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const auto whole = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("whole.h5"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  expect_same_results(tmp.file("r.h5"), tmp.file("whole.h5"));
}

namespace {
// A tmpfs of `size` bytes at `dir` (mounted, or remounted at the new size).
bool mount_tmpfs(const std::string& dir, long size, bool remount) {
  const std::string cmd = "mount -t tmpfs -o " + std::string(remount ? "remount," : "") +
                          "size=" + std::to_string(size) + " tmpfs " + dir + " 2>/dev/null";
  return std::system(cmd.c_str()) == 0;
}
}  // namespace

TEST(CliSweep, FullFilesystemStopsWithAResumableFile) {
  TempDir tmp;
  const std::string disk = tmp.file("disk");
  std::filesystem::create_directory(disk);
  if (!mount_tmpfs(disk, 200000, false)) GTEST_SKIP() << "cannot mount a tmpfs here (not root?)";
  struct Unmount {
    std::string dir;
    ~Unmount() { std::system(("umount " + dir).c_str()); }
  } unmount{disk};
  write_file(tmp.file("s.toml"), long_sweep);
  const std::string args = tmp.file("s.toml") + " --threads 1 --batch 100 -q -o " + disk + "/r.h5";
  const auto probe = run_chaosweep("sweep " + args);  // 200 kB: not even room for one batch
  ASSERT_EQ(probe.exit_code, 3) << probe.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(probe.err, m,
                                std::regex(R"(no room in \S+ for the next batch of \S+ \(needs up to (\d+) KiB)")))
      << probe.err;
  // Room for the first batch and a few more (tmpfs counts whole pages).
  const long size = long(std::filesystem::file_size(disk + "/r.h5.partial")) + std::stol(m[1]) * 1024 + 64 * 1024;
  ASSERT_TRUE(mount_tmpfs(disk, size, true));
  const auto r = run_chaosweep("sweep " + args + " --force");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("make room, then continue with --resume"), std::string::npos) << r.err;
  const std::int64_t kept = chaosweep::count_rows(disk + "/r.h5.partial");
  EXPECT_GE(kept, 100);
  EXPECT_LT(kept, long_sweep_runs);
  ASSERT_TRUE(mount_tmpfs(disk, 16 << 20, true));  // room again
  const auto resumed = run_chaosweep("sweep " + args + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const auto whole = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("whole.h5"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  expect_same_results(disk + "/r.h5", tmp.file("whole.h5"));
}

namespace {
// `args` must not replace the existing file `kept`: exit 2 naming it and
// --force, the file untouched; with --force it runs and replaces it.
void expect_refused_then_forced(const std::string& args, const std::string& kept) {
  write_file(kept, "keep me");
  const auto refused = run_chaosweep(args);
  EXPECT_EQ(refused.exit_code, 2) << args;
  EXPECT_NE(refused.err.find(kept + " exists; pass --force"), std::string::npos) << refused.err;
  EXPECT_EQ(chaosweep::test::read_file(kept), "keep me") << args;
  const auto forced = run_chaosweep(args + " --force");
  EXPECT_EQ(forced.exit_code, 0) << args << forced.err;
  EXPECT_NE(chaosweep::test::read_file(kept), "keep me") << args;
}
}  // namespace

TEST(CliSweep, ExistingOutputIsRefusedWithoutForce) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  expect_refused_then_forced("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("r.h5"), tmp.file("r.h5"));
  EXPECT_FALSE(std::filesystem::exists(tmp.file("r.h5.partial")));
  EXPECT_EQ(chaosweep::count_rows(tmp.file("r.h5")), 18);
}

TEST(CliSweep, UnwritableOutputIsNamedAndNothingIsRun) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  write_file(tmp.file("file"), "");
  // Root may write anywhere, so use a path no one can create: under a file.
  const auto r = run_chaosweep("sweep " + tmp.file("s.toml") + " -o " + tmp.file("file") + "/r.h5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(tmp.file("file")), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Not a directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("runs on"), std::string::npos) << r.out;  // stopped before the sweep began
}

TEST(CliMerge, ExistingOutputIsRefusedWithoutForce) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  const auto shard = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("all.h5"));
  ASSERT_EQ(shard.exit_code, 0) << shard.err;
  expect_refused_then_forced("merge -o " + tmp.file("m.h5") + " " + tmp.file("all.h5"), tmp.file("m.h5"));
  EXPECT_EQ(chaosweep::count_rows(tmp.file("m.h5")), 18);
}

TEST(CliSlurm, ADirectoryOfAnEarlierSlurmSweepIsRefusedWithoutForce) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  const std::string args = "slurm " + tmp.file("s.toml") + " -o " + tmp.file("run");
  ASSERT_EQ(run_chaosweep(args + " --tasks 2").exit_code, 0);
  const std::string before = chaosweep::test::read_file(tmp.file("run/cluster.toml"));
  const auto again = run_chaosweep(args + " --tasks 3");
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("already holds a chaosweep slurm sweep"), std::string::npos) << again.err;
  EXPECT_EQ(chaosweep::test::read_file(tmp.file("run/cluster.toml")), before);
  ASSERT_EQ(run_chaosweep(args + " --tasks 3 --force").exit_code, 0);
  EXPECT_NE(chaosweep::test::read_file(tmp.file("run/cluster.toml")).find("tasks = 3"), std::string::npos);
}

TEST(CliOutputs, TableFigureAndTraceRefuseAnExistingFileWithoutForce) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  const auto sweep = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("r.h5"));
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const std::string h5 = tmp.file("r.h5");
  struct Case {
    std::string command, kept;  // kept: the existing file the command would replace
  };
  const std::vector<Case> cases{
      {"table best " + h5 + " -o " + tmp.file("t.md"), "t.md"},
      {"figure heatmap " + h5 + " --x A --y B -o " + tmp.file("f.png"), "f.png"},
      {"figure heatmap " + h5 + " --x A --y B -o " + tmp.file("g.png"), "g.csv"},  // the CSV beside
      {"run --size 12 --max-time 100 --trace " + tmp.file("trace.csv"), "trace.csv"}};
  for (const Case& c : cases) {
    expect_refused_then_forced(c.command, tmp.file(c.kept));
    std::filesystem::remove(tmp.file(c.kept));
  }
}

// MathGL is loaded when a figure is drawn, not with the binary
// (analysis/mathgl.hpp: it costs every command ~40 ms as it loads). The
// dynamic loader names each library it opens under LD_DEBUG=files.
TEST(CliOutputs, MathGlIsLoadedOnlyToDrawAFigure) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), small_sweep);
  const auto sweep = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("r.h5"), "LD_DEBUG=files");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  ASSERT_NE(sweep.err.find("file=libtbb"), std::string::npos) << "the loader named no library:\n" << sweep.err;
  EXPECT_EQ(sweep.err.find("libmgl"), std::string::npos) << sweep.err;
  // HDF5 is linked statically: Debian's shared libhdf5 would bring libcurl
  // and ~30 more libraries into every command's start.
  EXPECT_EQ(sweep.err.find("libhdf5"), std::string::npos) << sweep.err;
  EXPECT_EQ(sweep.err.find("libcurl"), std::string::npos) << sweep.err;
  const auto figure =
      run_chaosweep("figure heatmap " + tmp.file("r.h5") + " --x A --y B -o " + tmp.file("f.png"), "LD_DEBUG=files");
  ASSERT_EQ(figure.exit_code, 0) << figure.err;
  EXPECT_NE(figure.err.find("file=libmgl"), std::string::npos) << figure.err;
  EXPECT_GT(std::filesystem::file_size(tmp.file("f.png")), 1000u);
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
  const auto r =
      run_chaosweep("sweep " + std::string(CHAOSWEEP_SOURCE_DIR) + "/experiments/demo.toml -o /tmp/x.h5 --shard 3/3");
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

// ------------------------------------------------------------ bounded memory

namespace {
// Peak RSS is measured against a baseline of the same build: under
// AddressSanitizer freed memory waits in a quarantine (up to 256 MiB) before
// it is reused, so a sweep's peak grows with what it ever allocated; the
// measured sweeps run without it (quarantine_size_mb=0: ASan's shadow,
// redzones and this build's coverage counters remain, a constant or a fixed
// fraction of what is live). The suite's other sweeps keep the quarantine.
// ThreadSanitizer's shadow and history multiply memory: the Release and
// Debug suites measure.
#if defined(CHAOSWEEP_TEST_TSAN)
#define SKIP_UNDER_TSAN() GTEST_SKIP() << "peak RSS is not meaningful under ThreadSanitizer"
#else
#define SKIP_UNDER_TSAN() (void)0
#endif

// Sets ASAN_OPTIONS for the sweeps this test starts, and puts it back.
class NoQuarantine {
 public:
  NoQuarantine() {
#if defined(CHAOSWEEP_TEST_ASAN)
    const char* old = std::getenv("ASAN_OPTIONS");
    if (old) old_ = old;
    setenv("ASAN_OPTIONS", (old_ ? *old_ + ":" : std::string()).append("quarantine_size_mb=0").c_str(), 1);
#endif
  }
  ~NoQuarantine() {
#if defined(CHAOSWEEP_TEST_ASAN)
    if (old_) {
      setenv("ASAN_OPTIONS", old_->c_str(), 1);
    } else {
      unsetenv("ASAN_OPTIONS");
    }
#endif
  }
  NoQuarantine(const NoQuarantine&) = delete;
  NoQuarantine& operator=(const NoQuarantine&) = delete;

 private:
  [[maybe_unused]] std::optional<std::string> old_;  // read under ASan only
};

// Peak RSS (KiB) of a whole sweep of `spec`.
long sweep_peak_rss(const TempDir& tmp, const std::string& name, const std::string& spec) {
  write_file(tmp.file(name + ".toml"), spec);
  const NoQuarantine no_quarantine;
  const int pid = chaosweep::test::start_chaosweep("sweep " + tmp.file(name + ".toml") + " -q --batch 1000 -o " +
                                                   tmp.file(name + ".h5"));
  long rss = 0;
  EXPECT_EQ(chaosweep::test::wait_exit(pid, &rss), 0);
  return rss;
}
}  // namespace

TEST(CliSweep, PeakMemoryDoesNotGrowWithTheNumberOfRuns) {
  SKIP_UNDER_TSAN();
  TempDir tmp;
  const long small = sweep_peak_rss(tmp, "small", cheap_sweep(10, 500));   // 5,000 runs
  const long large = sweep_peak_rss(tmp, "large", cheap_sweep(100, 500));  // 50,000 runs
  ASSERT_EQ(chaosweep::count_rows(tmp.file("large.h5")), 50000);
  // Ten times the runs, the same memory (rows go to disk a batch at a time).
  // The margin: one spec's peak RSS alone moves from process to process
  // (measured for the small sweep 22.5-28.4 MiB in Release and 52.6-59.0 MiB
  // under ASan, where CI once saw the small at 52.6 and the large at 60.8:
  // 8 MiB failed), so 16 MiB holds that noise plus 45,000 more runs at under
  // 100 bytes each; keeping the rows (~1 KiB a run) would add ~45 MiB.
  EXPECT_LT(large, small + 16384) << "peak RSS " << small << " KiB for 5,000 runs, " << large << " KiB for 50,000";
}

TEST(CliSweep, TenMillionRunSweepStartsAtOnceInBoundedMemory) {
  SKIP_UNDER_TSAN();
  TempDir tmp;
  const long small = sweep_peak_rss(tmp, "small", cheap_sweep(10, 500));  // 5,000 runs, whole
  write_file(tmp.file("big.toml"), cheap_sweep(100, 100000));             // 10^7 runs
  const std::string partial = tmp.file("big.h5.partial");
  long rss = 0;
  {
    const NoQuarantine no_quarantine;
    const int pid =
        chaosweep::test::start_chaosweep("sweep " + tmp.file("big.toml") + " -q --batch 1000 -o " + tmp.file("big.h5"));
    ASSERT_TRUE(wait_for_rows(partial, 3000, pid));
    kill(pid, SIGINT);
    EXPECT_EQ(chaosweep::test::wait_exit(pid, &rss), 130);
  }
  // The spec is expanded lazily: 10^7 runs cost little more than 5,000 (a
  // table of them, 8 bytes a run, would be 76 MiB), in any build ...
  EXPECT_LT(rss, small + 64 * 1024) << "peak RSS " << rss << " KiB, " << small << " KiB for a whole 5,000-run sweep";
#if !defined(CHAOSWEEP_TEST_SANITIZED)
  // ... and what a user's sweep of them costs, in Release.
  EXPECT_LT(rss, 100 * 1024) << "peak RSS " << rss << " KiB";
#endif
  const auto plan = chaosweep::test::run_chaosweep("plan " + tmp.file("big.toml"));
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  EXPECT_NE(plan.out.find("runs        10000000"), std::string::npos) << plan.out;
}

// The report's shape (speed itself is for BENCHMARKS.md, never asserted).
TEST(CliBench, JsonReportsEachWidthTheNaiveRatioAndTheWholeSweep) {
#if defined(CHAOSWEEP_TEST_SANITIZED)
  GTEST_SKIP() << "a bench of a sanitizer build measures the sanitizer; the Release suite runs it";
#endif
  const auto r = chaosweep::test::run_chaosweep("bench --json --seconds 0.05");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto number = [&](const std::string& key) {
    std::smatch m;
    const std::regex re("\"" + key + "\": ([-0-9.e+]+)");
    EXPECT_TRUE(std::regex_search(r.out, m, re)) << key << " missing in\n" << r.out;
    return m.empty() ? std::nan("") : std::stod(m[1]);
  };
  for (const char* target : {"scalar", "avx2", "avx512"}) {
    const std::regex width(
        "\\{\"target\": \"" + std::string(target) +
        "\", \"width\": [148], \"ns_per_lane_step\": ([0-9.]+), \"ns_per_lane_step_median\": ([0-9.]+)\\}");
    std::smatch m;
    const bool present = std::regex_search(r.out, m, width);
    if (std::string(target) == "scalar") {
      EXPECT_TRUE(present) << r.out;  // every CPU runs the portable width
    }
    if (!present) continue;
    EXPECT_GT(std::stod(m[1]), 0.0);
    EXPECT_LE(std::stod(m[1]), std::stod(m[2]));  // best round <= median round
  }
  EXPECT_EQ(number("rounds"), 5);
  EXPECT_GT(number("naive_scalar_glibc_ns_per_step"), 0.0);
  EXPECT_GT(number("best_vs_naive"), 1.0);  // any width beats glibc sin/cos called 24 times a step
  EXPECT_GT(number("best_vs_naive_median"), 1.0);
  EXPECT_EQ(number("sweep_runs"), 2048);
  EXPECT_GT(number("sweep_runs_per_s"), 0.0);
  EXPECT_GT(number("scaling_2_threads"), 0.0);
  EXPECT_TRUE(std::isfinite(number("sweep_overhead")));
  EXPECT_NE(r.out.find("\"cpu_best\": \""), std::string::npos);
  EXPECT_EQ(r.out.back() == '\n' ? r.out[r.out.size() - 2] : r.out.back(), '}');
}

// --variants: every cell (6 technique sets x 50/200 m x SR 1/4 x open/five
// squares) once per round, with finite positive ns per step and ratios that
// are the quotient of the reported ns values (one round), or the median of
// the rounds' ratios, between their least and greatest (two rounds: the
// mean of the two). Tiny runs keep it fast; speed itself is for BENCHMARKS.md.
TEST(CliBench, VariantsReportEveryCellWithConsistentRatios) {
  for (const int rounds : {1, 2}) {
    const auto r = chaosweep::test::run_chaosweep(
        "bench --variants --json --variant-runs 3 --variant-time 20 "
        "--variant-rounds " +
        std::to_string(rounds));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string num = "([-0-9.e+naif]+)";
    const std::regex cell(
        "\\{\"size\": ([0-9]+), \"sr\": ([0-9]+), \"env\": \"([a-z_]+)\", \"variant\": \"([A-Za-z+]+)\", "
        "\"runs\": 3, \"arnold_steps\": ([0-9]+), \"transit_points\": ([0-9]+), \"seconds\": " +
        num + ", \"ns_per_step\": " + num + ", \"ratio\": " + num + ", \"ratio_min\": " + num +
        ", \"ratio_max\": " + num + "\\}");
    struct Cell {
      double ns, ratio, lo, hi;
    };
    std::map<std::string, Cell> cells;
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), cell); it != std::sregex_iterator(); ++it) {
      const std::smatch& m = *it;
      const std::string key = m[1].str() + "/" + m[2].str() + "/" + m[3].str() + "/" + m[4].str();
      EXPECT_GT(std::stod(m[5]) + std::stod(m[6]), 0.0) << key;
      const Cell c{std::stod(m[8]), std::stod(m[9]), std::stod(m[10]), std::stod(m[11])};
      EXPECT_TRUE(cells.emplace(key, c).second) << "twice: " << key;
    }
    ASSERT_EQ(cells.size(), 48u) << r.out;
    for (const char* size : {"50", "200"})
      for (const char* sr : {"1", "4"}) {
        const std::string map = std::string(size) + "/" + sr + "/";
        const auto base = cells.find(map + "open/original");
        ASSERT_NE(base, cells.end()) << map;
        for (const char* env : {"open", "five_squares"})
          for (const char* v : {"original", "IS", "SC", "MZ", "IS+MZ+SC", "logistic"}) {
            const auto c = cells.find(map + env + "/" + v);
            ASSERT_NE(c, cells.end()) << map << env << "/" << v;
            const Cell& x = c->second;
            EXPECT_TRUE(std::isfinite(x.ns) && x.ns > 0) << c->first;
            EXPECT_TRUE(std::isfinite(x.ratio) && x.ratio > 0) << c->first;
            EXPECT_LE(x.lo, x.ratio * (1 + 1e-3)) << c->first;
            EXPECT_GE(x.hi, x.ratio * (1 - 1e-3)) << c->first;
            if (rounds == 1) {
              EXPECT_NEAR(x.ratio, x.ns / base->second.ns, 1e-3 * x.ratio + 1e-4) << c->first;
              EXPECT_NEAR(x.lo, x.hi, 1e-3 * x.ratio + 1e-4) << c->first;
            } else {
              EXPECT_NEAR(x.ratio, 0.5 * (x.lo + x.hi), 1e-3 * x.ratio + 1e-4) << c->first;
            }
          }
        EXPECT_NEAR(base->second.ratio, 1.0, 1e-9);
        EXPECT_NEAR(base->second.lo, 1.0, 1e-9);
        EXPECT_NEAR(base->second.hi, 1.0, 1e-9);
      }
    EXPECT_NE(r.out.find("\"runs_per_cell\": 3"), std::string::npos);
    EXPECT_NE(r.out.find("\"rounds\": " + std::to_string(rounds)), std::string::npos);
    EXPECT_NE(r.out.find("\"threads\": 1"), std::string::npos);
  }
  // The default table names every variant in its header.
  const auto t = chaosweep::test::run_chaosweep("bench --variants --variant-runs 1 --variant-time 5");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("| map | original | IS | SC | MZ | IS+MZ+SC | logistic |"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("| 200 m SR 4 five_squares | "), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("the median of 3 rounds"), std::string::npos) << t.out;
  for (const char* bad_flag : {"--variant-runs 0", "--variant-rounds 0", "--variant-rounds 100"}) {
    const auto bad = chaosweep::test::run_chaosweep(std::string("bench --variants ") + bad_flag);
    EXPECT_EQ(bad.exit_code, 2) << bad_flag;
    EXPECT_NE(bad.err.find(std::string(bad_flag).substr(0, std::string(bad_flag).find(' '))), std::string::npos)
        << bad.err;
  }
}

TEST(CliBench, PipelineMeasuresOneTargetAndRefusesAnUnknownOne) {
  const auto r = chaosweep::test::run_chaosweep("bench --pipeline scalar --seconds 0.01");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(std::stod(r.out), 0.0) << r.out;  // ns per lane-step, alone on its line
  const auto bad = chaosweep::test::run_chaosweep("bench --pipeline avx3");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--pipeline: avx3 not in {scalar,avx2,avx512}"), std::string::npos) << bad.err;
  const auto zero = chaosweep::test::run_chaosweep("bench --seconds 0");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("--seconds"), std::string::npos) << zero.err;
}

// `chaosweep log`: every sweep that started writing, with what it left.
TEST(CliLog, ListsFinishedRunningStoppedAndKilledSweepsWithTheirRows) {
  TempDir tmp;
  const std::string history = tmp.file("history.tsv");
  setenv("CHAOSWEEP_HISTORY", history.c_str(), 1);  // the children inherit it
  // Long enough to be still running when killed after `log` ran (12,000
  // runs took 0.3 s once the writes left the sweep's thread).
  constexpr int b_values = 2000, runs = 24 * b_values;
  write_file(tmp.file("s.toml"), cheap_sweep(24, b_values));
  write_file(tmp.file("small.toml"), chaosweep::test::small_spec_18_runs("log-small"));
  ASSERT_EQ(run_chaosweep("sweep " + tmp.file("small.toml") + " -q -o " + tmp.file("done.h5")).exit_code, 0);
  for (const int sig : {SIGINT, SIGKILL}) {
    const std::string out = tmp.file(sig == SIGINT ? "stopped.h5" : "killed.h5");
    const int pid =
        chaosweep::test::start_chaosweep("sweep " + tmp.file("s.toml") + " --threads 1 --batch 1000 -q -o " + out);
    ASSERT_TRUE(wait_for_rows(out + ".partial", 1000, pid));
    const auto live = run_chaosweep("log --last 1");
    EXPECT_NE(live.out.find("running"), std::string::npos) << live.out;
    EXPECT_NE(live.out.find(out + " <- "), std::string::npos) << live.out;
    kill(pid, sig);
    chaosweep::test::wait_exit(pid);
  }
  // Refused before it writes (an existing output without --force): not a sweep that ran.
  EXPECT_EQ(run_chaosweep("sweep " + tmp.file("small.toml") + " -q -o " + tmp.file("done.h5")).exit_code, 2);
  const auto log = run_chaosweep("log");
  unsetenv("CHAOSWEEP_HISTORY");
  ASSERT_EQ(log.exit_code, 0) << log.err;
  auto line_of = [&](const std::string& out) {
    const auto at = log.out.find(tmp.file(out) + " <- ");
    if (at == std::string::npos) return std::string();
    const auto begin = log.out.rfind('\n', at) + 1;
    return log.out.substr(begin, log.out.find('\n', at) - begin);
  };
  EXPECT_NE(line_of("done.h5").find("finished"), std::string::npos) << log.out;
  EXPECT_NE(line_of("done.h5").find("of 18 "), std::string::npos) << log.out;
  EXPECT_NE(line_of("done.h5").find(tmp.file("small.toml")), std::string::npos) << log.out;
  EXPECT_NE(line_of("stopped.h5").find("stopped (SIGINT), resumable"), std::string::npos) << log.out;
  EXPECT_NE(line_of("stopped.h5").find(" of " + std::to_string(runs) + " done"), std::string::npos) << log.out;
  EXPECT_NE(line_of("killed.h5").find("killed, resumable"), std::string::npos) << log.out;
  EXPECT_EQ(log.out.find(tmp.file("done.h5") + " <- "), log.out.rfind(tmp.file("done.h5") + " <- ")) << log.out;
  // A history that cannot be written costs the sweep nothing but a warning.
  const auto unrecorded = run_chaosweep("sweep " + tmp.file("small.toml") + " -o " + tmp.file("u.h5"),
                                        "env CHAOSWEEP_HISTORY=/proc/no/such/history.tsv");
  EXPECT_EQ(unrecorded.exit_code, 0) << unrecorded.err;
  EXPECT_NE(unrecorded.err.find("cannot record the sweep"), std::string::npos) << unrecorded.err;
}
