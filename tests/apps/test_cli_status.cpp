// `chaosweep status` with SLURM asked: fake squeue, sacct, scontrol and
// sbatch scripts on PATH (and nothing else on it) stand for a cluster in each
// state; a lock held by this process stands for a live writer without SLURM.
// tests/slurm_integration.sh does the same against a real SLURM.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "apps/chaosweep/slurm_query.hpp"
#include "apps/chaosweep/slurm_values.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/output_lock.hpp"
#include "tests/support/test_util.hpp"

namespace {

using chaosweep::shell_quote;
using chaosweep::test::has;
using chaosweep::test::read_file;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;
namespace fs = std::filesystem;

// Occurrences of `part` in `text`.
int count(const std::string& text, const std::string& part) {
  int n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// A `chaosweep slurm` directory of 6 shards of 10 runs, array job 500
// recorded: shard 0 finished, 1, 3 and 5 partial (4 rows), 2 and 4 missing.
struct Cluster {
  TempDir tmp;
  std::string dir = tmp.file("run"), bin = tmp.file("bin");

  Cluster(bool recorded = true) {
    fs::create_directories(dir + "/logs");
    fs::create_directories(bin);
    write_file(dir + "/cluster.toml", "spec = '/x.toml'\nname = 'x'\ntasks = 6\nruns = 60\n");
    if (recorded) write_file(dir + "/jobs.txt", "array 500\nmerge 501\n");
    shard(dir + "/shard_0.h5", 0, 10);
    for (int k : {1, 3, 5}) {
      shard(tmp.file("p.h5"), k, 4);
      fs::rename(tmp.file("p.h5"), dir + "/shard_" + std::to_string(k) + ".h5.partial");
    }
  }
  // Rows k, k + 6, ... of a result file, as a sweep --shard k/6 writes them.
  static void shard(const std::string& path, int k, int rows) {
    std::vector<chaosweep::RunRow> out(static_cast<std::size_t>(rows));
    for (int j = 0; j < rows; ++j) {
      out[std::size_t(j)].tuple.run_id = k + 6 * j;
      out[std::size_t(j)].tuple.params = chaosweep::test::small_run(10);
    }
    // The attributes merge (and so status) checks of a finished shard.
    chaosweep::H5RunWriter w(path, chaosweep::H5RunWriter::Mode::create,
                             {{"spec_hash", std::string("h")},
                              {"inputs_hash", std::string("h")},
                              {"input_files", std::string()},
                              {"shard", std::to_string(k) + "/6"},
                              {"runs_total", std::int64_t(60)}});
    w.append(out);
    w.finish();
  }
  // A fake SLURM client: logs its argv, one word a line, to bin/NAME.args,
  // prints `out`, `err` on stderr, exits `rc`. Only shell built-ins: PATH
  // holds bin/ alone.
  void fake(const std::string& name, const std::string& out, int rc = 0, const std::string& err = "") const {
    const std::string path = bin + "/" + name;
    write_file(path, "#!/bin/sh\nprintf '%s\\n' \"$@\" >>" + shell_quote(path + ".args") + "\nprintf %s " +
                         shell_quote(out) + "\nprintf %s " + shell_quote(err) + " >&2\nexit " + std::to_string(rc) +
                         "\n");
    chmod(path.c_str(), 0755);
  }
  chaosweep::test::CommandResult status() const {
    return run_chaosweep("status " + shell_quote(dir), "timeout 60 env PATH=" + shell_quote(bin));
  }
};

}  // namespace

TEST(CliStatusSlurm, LiveTasksAreRunningOrPendingAndDeadOnesAreResubmittedWithTheirState) {
  Cluster c;
  c.fake("squeue", "500|1|RUNNING\n500|2|PENDING\n");
  c.fake("sacct", "500_0|COMPLETED|0:0\n500_1|RUNNING|0:0\n500_3|FAILED|1:0\n500_4|CANCELLED by 1000|0:15\n");
  const auto r = c.status();
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.out, "SLURM array job: 500\n")) << r.out;
  EXPECT_TRUE(has(r.out, "finished 1: 0\n")) << r.out;
  EXPECT_TRUE(has(r.out, "running  1: 1\n")) << r.out;
  EXPECT_TRUE(has(r.out, "  shard 1: 4 of 10 runs, job 500_1 RUNNING\n")) << r.out;
  EXPECT_TRUE(has(r.out, "pending  1: 2\n")) << r.out;
  // Ended otherwise than COMPLETED: failed, with the rows left (or none).
  EXPECT_TRUE(has(r.out,
                  "failed   2: 3,4\n  shard 3: 4 of 10 runs; job 500_3 FAILED (exit 1:0), no lock\n"
                  "  shard 4: no rows; job 500_4 CANCELLED (exit 0:15), no lock\n"))
      << r.out;
  EXPECT_TRUE(has(r.out, "partial  1: 5\n  shard 5: 4 of 10 runs; no job and no lock\n")) << r.out;
  EXPECT_TRUE(has(r.out, "missing  0: -\n")) << r.out;
  EXPECT_TRUE(has(r.out, "resubmit: --array=3,4,5\n")) << r.out;
  EXPECT_FALSE(has(r.out, "note:")) << r.out;
  // The ids go in as argv words of their own, in the forms parsed.
  EXPECT_EQ(read_file(c.bin + "/squeue.args"), "-h\n-r\n-j\n500\n-o\n%F|%K|%T\n");
  EXPECT_EQ(read_file(c.bin + "/sacct.args"), "-n\n-P\n-X\n-j\n500\n-o\nJobID,State,ExitCode\n");
  EXPECT_FALSE(fs::exists(c.bin + "/scontrol.args")) << "sacct answered";
}

TEST(CliStatusSlurm, AResubmissionOutranksTheFailureBeforeIt) {
  Cluster c;
  write_file(c.dir + "/logs/task_3.job", "502\n");  // written by task 3's script under job 502
  c.fake("squeue", "502|3|RUNNING\n");
  c.fake("sacct", "500_3|TIMEOUT|0:0\n502_3|RUNNING|0:0\n500_5|TIMEOUT|0:0\n502_5|COMPLETED|0:0\n");
  const auto r = c.status();
  EXPECT_TRUE(has(r.out, "SLURM array jobs: 500 502\n")) << r.out;
  EXPECT_TRUE(has(r.out, "running  1: 3\n")) << r.out;
  EXPECT_TRUE(has(r.out, "  shard 5: 4 of 10 runs; job 502_5 COMPLETED (exit 0:0), no lock\n")) << r.out;
  EXPECT_EQ(read_file(c.bin + "/squeue.args").find("-j\n500,502\n"), 6u) << read_file(c.bin + "/squeue.args");
}

TEST(CliStatusSlurm, WithoutAccountingStorageEndedTasksComeFromScontrol) {
  Cluster c;
  c.fake("squeue", "");
  c.fake("sacct", "", 1, "sacct: error: Slurm accounting storage is disabled\n");
  c.fake("scontrol",
         "JobId=503 ArrayJobId=500 ArrayTaskId=3 JobName=x JobState=FAILED Reason=NonZeroExitCode ExitCode=2:0\n"
         "JobId=500 ArrayJobId=500 ArrayTaskId=4-5%2 JobState=PENDING Reason=JobArrayTaskLimit ExitCode=0:0\n");
  const auto r = c.status();
  EXPECT_EQ(count(r.out, "note: "), 1) << r.out;
  EXPECT_TRUE(has(r.out,
                  "note: sacct failed (sacct: error: Slurm accounting storage is disabled): ended tasks "
                  "from scontrol show job"))
      << r.out;
  EXPECT_TRUE(has(r.out, "failed   1: 3\n  shard 3: 4 of 10 runs; job 500_3 FAILED (exit 2:0), no lock\n")) << r.out;
  EXPECT_TRUE(has(r.out, "pending  2: 4,5\n  shard 5: 4 of 10 runs, job 500_5 PENDING\n")) << r.out;
  EXPECT_TRUE(has(r.out, "resubmit: --array=1,2,3\n")) << r.out;
  EXPECT_EQ(read_file(c.bin + "/scontrol.args"), "-o\nshow\njob\n500\n");
}

TEST(CliStatusSlurm, MissingClientsLeaveTheLocksToDecideSaidOnce) {
  Cluster c;  // bin/ is empty: no squeue, sacct or scontrol
  const auto r = c.status();
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(count(r.out, "note: "), 1) << r.out;
  EXPECT_TRUE(has(r.out, "note: squeue is not on PATH: SLURM not asked, states from the shard locks only\n")) << r.out;
  EXPECT_TRUE(has(r.out, "  shard 1: 4 of 10 runs; no job and no lock\n")) << r.out;
  EXPECT_TRUE(has(r.out, "resubmit: --array=1,2,3,4,5\n")) << r.out;
  // squeue there but failing (no controller), no sacct nor scontrol: two notes, still the locks.
  c.fake("squeue", "", 1, "squeue: error: Unable to contact slurm controller (connect failure)\n");
  const auto f = c.status();
  EXPECT_EQ(count(f.out, "note: "), 2) << f.out;
  EXPECT_TRUE(has(f.out, "note: squeue failed (squeue: error: Unable to contact slurm controller")) << f.out;
  EXPECT_TRUE(has(f.out, "note: sacct is not on PATH and scontrol is not either: ended tasks unknown\n")) << f.out;
  EXPECT_TRUE(has(f.out, "resubmit: --array=1,2,3,4,5\n")) << f.out;
}

TEST(CliStatusSlurm, AJobIdThatIsNotANumberIsNotPassedOn) {
  Cluster c(false);
  write_file(c.dir + "/jobs.txt", "array 500;touch\narray -x\n");
  c.fake("squeue", "");
  const auto r = c.status();
  EXPECT_TRUE(has(r.out, "note: job id '500;touch' is not a number: not asked\n")) << r.out;
  EXPECT_TRUE(has(r.out, "note: job id '-x' is not a number: not asked\n")) << r.out;
  EXPECT_FALSE(fs::exists(c.bin + "/squeue.args")) << "no valid id: SLURM not asked";
}

// No SLURM at all: a lock held (here, by this process) marks a live writer;
// a lock file nobody holds (its writer was killed) and a FIFO in a lock's
// place do not, and neither makes status wait.
TEST(CliStatusSlurm, AHeldLockIsALiveWriterWithoutSlurm) {
  Cluster c(false);
  const chaosweep::OutputLock lock(c.dir + "/shard_1.h5");
  write_file(c.dir + "/shard_3.h5.lock", "process 1 on gone\n");
  ASSERT_EQ(mkfifo((c.dir + "/shard_5.h5.lock").c_str(), 0644), 0);
  const auto start = std::chrono::steady_clock::now();
  const auto r = c.status();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(count(r.out, "note: "), 1) << r.out;
  EXPECT_TRUE(has(r.out, "note: no SLURM job recorded in ")) << r.out;
  EXPECT_TRUE(
      has(r.out, "running  1: 1\n  shard 1: 4 of 10 runs, written by process " + std::to_string(getpid()) + " on "))
      << r.out;
  EXPECT_TRUE(has(r.out, "partial  2: 3,5\n")) << r.out;
  EXPECT_TRUE(has(r.out, "resubmit: --array=2,3,4,5\n")) << r.out;
}

TEST(CliStatusSlurm, EveryShardLiveLeavesNothingToResubmit) {
  Cluster c;
  c.fake("squeue", "500|[1-5]|PENDING\n");
  c.fake("sacct", "");
  const auto r = c.status();
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has(r.out, "pending  5: 1,2,3,4,5\n")) << r.out;
  EXPECT_TRUE(has(r.out, "nothing to resubmit: every shard not finished has a live task\n")) << r.out;
  EXPECT_FALSE(has(r.out, "--array=")) << r.out;
}

TEST(SlurmQuery, ParsersReadRangesThrottlesAndSkipWhatTheyCannotRead) {
  chaosweep::TaskStates t;
  chaosweep::parse_sacct(
      "7_[2-4,9%2]|PENDING|0:0\n7_1|OUT_OF_MEMORY|0:125\n7|COMPLETED|0:0\n7_x|FAILED|1:0\n"
      "8_1|lowercase|1:0\n8_0|FAILED|$(id)\n",
      6, t);
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t.at(2).state, "PENDING");
  EXPECT_EQ(t.at(4).job, 7);
  EXPECT_EQ(t.count(9), 0u) << "beyond the plan's tasks";
  EXPECT_EQ(t.at(1).exit_code, "0:125");
  EXPECT_EQ(t.at(0).state, "FAILED");
  EXPECT_EQ(t.at(0).exit_code, "") << "an exit code not of the form N:M is dropped";
  // Live outranks ended whatever the order; among ended, the later job.
  chaosweep::merge_task_state(t, 1, {6, "RUNNING", ""});
  chaosweep::merge_task_state(t, 1, {9, "FAILED", "1:0"});
  EXPECT_EQ(t.at(1).state, "RUNNING");
  chaosweep::merge_task_state(t, 0, {9, "TIMEOUT", ""});
  chaosweep::merge_task_state(t, 0, {5, "COMPLETED", ""});
  EXPECT_EQ(t.at(0).state, "TIMEOUT");
  EXPECT_TRUE(chaosweep::slurm_state_live("COMPLETING"));
  EXPECT_FALSE(chaosweep::slurm_state_live("PREEMPTED"));
}

// --submit runs sbatch by argv and records both job ids for status; task
// scripts record the job they run under.
TEST(CliSlurm, SubmitRecordsTheJobIdsAndTheTasksRecordTheirOwn) {
  Cluster c;
  write_file(c.tmp.file("s.toml"), chaosweep::test::small_spec_18_runs("sub"));
  const std::string args = c.tmp.file("sbatch.args");
  // The first call (the array) prints 700, the second (the merge) 701;cluster.
  write_file(c.bin + "/sbatch", "#!/bin/sh\nprintf '%s\\n' \"$@\" >>" + shell_quote(args) + "\nif [ -e " +
                                    shell_quote(args + ".n") + " ]; then printf '701;c\\n'; else : >" +
                                    shell_quote(args + ".n") + "; printf '700\\n'; fi\n");
  chmod((c.bin + "/sbatch").c_str(), 0755);
  const std::string run = c.tmp.file("sub");
  const auto r = run_chaosweep("slurm " + c.tmp.file("s.toml") + " --tasks 3 -o " + run + " --submit",
                               "env PATH=" + shell_quote(c.bin));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "submitted array job 700 and merge job 701 (recorded in " + run + "/jobs.txt)")) << r.out;
  EXPECT_EQ(read_file(run + "/jobs.txt"), "array 700\nmerge 701\n");
  EXPECT_EQ(read_file(args),
            "--parsable\n" + run + "/sweep.sbatch\n--parsable\n--dependency=afterok:700\n" + run + "/merge.sbatch\n");
  // No sbatch on PATH: the scripts stay, the error says so (exit 3).
  const auto none = run_chaosweep("slurm " + c.tmp.file("s.toml") + " --tasks 3 --force -o " + run + " --submit",
                                  "env PATH=" + shell_quote(c.tmp.file("nothing")));
  EXPECT_EQ(none.exit_code, 3);
  EXPECT_TRUE(has(none.err, "sbatch is not on PATH")) << none.err;
  // The merge refused after the array went in: exit 3, the array named, its id recorded.
  write_file(c.bin + "/sbatch",
             "#!/bin/sh\ncase \"$2\" in --dependency=*) printf 'sbatch: error: Invalid dependency\\n' "
             ">&2; exit 1;; esac\nprintf '800\\n'\n");
  const auto half = run_chaosweep("slurm " + c.tmp.file("s.toml") + " --tasks 3 --force -o " + run + " --submit",
                                  "env PATH=" + shell_quote(c.bin));
  EXPECT_EQ(half.exit_code, 3);
  EXPECT_TRUE(has(half.err,
                  "sbatch failed for the merge job: sbatch: error: Invalid dependency (array job 800 was "
                  "submitted; submit " +
                      run + "/merge.sbatch by hand)"))
      << half.err;
  EXPECT_EQ(read_file(run + "/jobs.txt"), "array 700\nmerge 701\narray 800\n");
  // Task 1's script, run as SLURM would under array job 702, records 702.
  const std::string cmd = "cd " + shell_quote(c.tmp.path().string()) +
                          " && env SLURM_ARRAY_JOB_ID=702 SLURM_ARRAY_TASK_ID=1 SLURM_CPUS_PER_TASK=1 bash " +
                          shell_quote(run + "/sweep.sbatch") + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(read_file(run + "/logs/task_1.job"), "702\n");
  c.fake("squeue", "");
  c.fake("sacct", "");
  const auto st = run_chaosweep("status " + run, "env PATH=" + shell_quote(c.bin));
  EXPECT_TRUE(has(st.out, "SLURM array jobs: 700 800 702\n")) << st.out;
  EXPECT_TRUE(has(st.out, "finished 1: 1\n")) << st.out;
}
