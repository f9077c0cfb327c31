// Inputs checked before any work (issue 18, docs/inputs.md): output paths
// that could never be written, SLURM array variables that are not numbers,
// and input files that are not regular files are refused with exit 2 before
// the first run, and nothing is written.
#include <gtest/gtest.h>

#include <hdf5.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/rows/run_hash.hpp"
#include "engine/store/h5_store.hpp"
#include "tests/support/test_util.hpp"

using chaosweep::test::has;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

namespace fs = std::filesystem;

const char* tiny_sweep = "[fixed]\nsize = 10\nsr = 2\nmax_time = 5\n[axes]\nA = [0.4, 0.5]\n";

// tiny_sweep on the environment `env`.
std::string tiny_sweep_on(const std::string& env) {
  return "[fixed]\nenv = \"" + env + "\"\nsize = 10\nsr = 2\nmax_time = 5\n[axes]\nA = [0.4, 0.5]\n";
}

// As a file written before inputs_hash was recorded.
void delete_attribute(const std::string& path, const char* name) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0) << path;
  EXPECT_GE(H5Adelete(f, name), 0) << name;
  H5Fclose(f);
}

// Every file directly in `dir`.
std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST(CliSweep, AnOutputPathThatCannotBeAFileIsRefusedBeforeTheFirstRun) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), tiny_sweep);
  fs::create_directory(tmp.file("work"));
  fs::create_directory(tmp.file("work/outdir"));
  const std::string in_work = "cd " + tmp.file("work") + " &&";
  struct Case {
    std::string args, message;
  };
  for (const Case& c :
       {Case{"-o ''", "-o: the output path is empty: give a file name"},
        Case{"-o outdir", "-o: outdir is a directory: give a file name (e.g. outdir/results.h5)"},
        Case{"-o outdir --force", "-o: outdir is a directory"}, Case{"-o outdir --resume", "-o: outdir is a directory"},
        Case{"-o new/", "-o: new/ names a directory, not a file"},
        Case{"-o outdir/..", "-o: outdir/.. is a directory"}}) {
    const auto r = run_chaosweep("sweep " + tmp.file("s.toml") + " " + c.args, in_work);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_TRUE(has(r.err, "chaosweep sweep: " + c.message)) << c.args << ": " << r.err;
    EXPECT_FALSE(has(r.out, "runs on")) << c.args;  // refused before the sweep began
    EXPECT_EQ(files_in(tmp.file("work")), std::vector<std::string>{"outdir"}) << c.args;
    EXPECT_TRUE(fs::is_empty(tmp.file("work/outdir"))) << c.args;
  }
  // Every command that writes a file refuses a directory, --force or not.
  write_file(tmp.file("work/r.h5"), "");
  for (const char* cmd :
       {"merge -o outdir r.h5", "table summary -o outdir --force r.h5", "run --trace outdir --force --size 10"}) {
    const auto r = run_chaosweep(cmd, in_work);
    EXPECT_EQ(r.exit_code, 2) << cmd << ": " << r.err;
    EXPECT_TRUE(has(r.err, "outdir is a directory")) << cmd << ": " << r.err;
  }
}

TEST(CliSweep, BadSlurmArrayVariablesAreNamedAndNothingRuns) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), tiny_sweep);
  const std::string sweep = "sweep " + tmp.file("s.toml") + " -o " + tmp.file("r.h5");
  struct Case {
    std::string env, message;
  };
  for (const Case& c :
       {Case{"SLURM_ARRAY_TASK_ID=abc SLURM_ARRAY_TASK_COUNT=2",
             "SLURM_ARRAY_TASK_ID = 'abc' is not a whole number in [0, 2147483647]"},
        Case{"SLURM_ARRAY_TASK_ID=abc", "SLURM_ARRAY_TASK_ID = 'abc' is not a whole number"},
        Case{"SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2x", "SLURM_ARRAY_TASK_COUNT = '2x' is not a whole number"},
        Case{"SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=-1",
             "SLURM_ARRAY_TASK_MIN = '-1' is not a whole number"},
        Case{"SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_STEP=", "SLURM_ARRAY_TASK_STEP = ''"},
        Case{"SLURM_ARRAY_TASK_ID=99999999999 SLURM_ARRAY_TASK_COUNT=2", "SLURM_ARRAY_TASK_ID = '99999999999'"},
        Case{"SLURM_ARRAY_TASK_ID=1", "SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not"},
        Case{"SLURM_ARRAY_TASK_COUNT=2", "SLURM_ARRAY_TASK_COUNT is set but SLURM_ARRAY_TASK_ID is not"},
        Case{
            "SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=2",
            "SLURM_ARRAY_TASK_ID = 2, SLURM_ARRAY_TASK_MIN = 0, SLURM_ARRAY_TASK_STEP = 1, SLURM_ARRAY_TASK_COUNT = 2: "
            "not a task of the array"},
        Case{"SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_STEP=2", "not a task of the array"}}) {
    const auto r = run_chaosweep(sweep, "env " + c.env);
    EXPECT_EQ(r.exit_code, 2) << c.env << ": " << r.err;
    EXPECT_TRUE(has(r.err, "chaosweep sweep: SLURM_ARRAY_TASK_")) << c.env << ": " << r.err;
    EXPECT_TRUE(has(r.err, c.message)) << c.env << ": " << r.err;
    EXPECT_FALSE(fs::exists(tmp.file("r.h5")) || fs::exists(tmp.file("r.h5.partial"))) << c.env;
  }
  // Good values pick the shard: task 12 of an array 10-12 with step 2 is shard 1 of 2.
  const auto r = run_chaosweep(
      sweep, "env SLURM_ARRAY_TASK_ID=12 SLURM_ARRAY_TASK_MIN=10 SLURM_ARRAY_TASK_STEP=2 SLURM_ARRAY_TASK_COUNT=2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "(shard 1/2 of 2)")) << r.out;
  // --shard wins over the variables, bad or not.
  fs::remove(tmp.file("r.h5"));
  const auto own = run_chaosweep(sweep + " --shard 0/1", "env SLURM_ARRAY_TASK_ID=abc");
  EXPECT_EQ(own.exit_code, 0) << own.err;
}

TEST(CliSweep, InputsThatAreNotRegularFilesAreRefusedAndNothingIsWritten) {
  TempDir tmp;
  ASSERT_EQ(mkfifo(tmp.file("fifo").c_str(), 0600), 0);
  fs::create_directory(tmp.file("dir"));
  const std::string out = tmp.file("r.h5");
  struct Case {
    std::string spec, message;
  };
  for (const Case& c :
       {Case{"", tmp.file("fifo") + ": the sweep spec is a FIFO (named pipe), not a regular file"},
        Case{"[sweep]\nextends = \"/dev/zero\"\n", "/dev/zero: the spec named by sweep.extends is a character device"},
        Case{"[sweep]\nextends = \"dir\"\n", "dir: the spec named by sweep.extends is a directory, not a regular file"},
        Case{tiny_sweep_on("/dev/zero"),
             "fixed: environment /dev/zero: the environment file is a character device, not a regular file"},
        Case{tiny_sweep_on(tmp.file("fifo")), "the environment file is a FIFO"},
        Case{tiny_sweep_on(tmp.file("dir") + "/"), "the environment file is a directory, not a regular file"},
        Case{"# nothing\n", "the spec is empty (it sets nothing)"}}) {
    std::string spec = tmp.file("fifo");
    if (!c.spec.empty()) {
      spec = tmp.file("s.toml");
      write_file(spec, c.spec);
    }
    for (const std::string& cmd : {"sweep " + spec + " -q -o " + out, "plan " + spec}) {
      const auto r = run_chaosweep(cmd);
      EXPECT_EQ(r.exit_code, 2) << cmd << ": " << r.err;
      EXPECT_TRUE(has(r.err, c.message)) << cmd << ": " << r.err;
      EXPECT_FALSE(fs::exists(out) || fs::exists(out + ".partial")) << cmd;
    }
  }
  const auto r = run_chaosweep("sweep /dev/null -q -o " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "/dev/null: the sweep spec is a character device, not a regular file")) << r.err;
}

TEST(CliPlan, ABillionRunSpecIsPlannedWithoutVisitingEveryRun) {
  // plan visited every run (1e9: about 9 minutes); now it walks the axes
  // that set time budgets (none here), so it ends well inside the test's timeout.
  TempDir tmp;
  write_file(tmp.file("s.toml"),
             "[fixed]\nsize = 10\nsr = 2\nmax_time = 5\n[axes]\nA = { start = 0.1, stop = 0.9, num = 1000 }\n"
             "B = { start = 0.1, stop = 0.9, num = 1000 }\nC = { start = 0.1, stop = 0.9, num = 1000 }\n");
  const auto r = run_chaosweep("plan " + tmp.file("s.toml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "runs        1000000000  (1000 x 1000 x 1000)")) << r.out;
  EXPECT_TRUE(has(r.out, "work        at most 5e+10 integration steps")) << r.out;
}

// Provenance names each file read by its absolute path (an environment path
// is found from the working directory, so a relative one would not say later
// which file it was) with its content hash: the spec, the spec it extends
// (found from the spec's directory) and the environment.
TEST(CliSweep, InputFilesRecordEachFilesAbsolutePathAndContentHash) {
  TempDir tmp;
  fs::create_directories(tmp.file("sub"));
  fs::create_directories(tmp.file("maps"));
  const std::string env = "obstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n";
  const std::string parent = tiny_sweep_on("maps/../maps/env1.toml");
  const std::string child = "[sweep]\nextends = \"parent.toml\"\n[fixed]\nlabel = \"child\"\n";
  write_file(tmp.file("maps/env1.toml"), env);
  write_file(tmp.file("sub/parent.toml"), parent);
  write_file(tmp.file("sub/child.toml"), child);
  const auto r = run_chaosweep("sweep sub/child.toml -q -o r.h5", "cd " + tmp.path().string() + " &&");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  using chaosweep::fnv1a64, chaosweep::hex64;
  const std::string want = "spec\t" + hex64(fnv1a64(child)) + "\t" + tmp.file("sub/child.toml") + "\t" +
                           tmp.file("sub/child.toml") + "\nextends\t" + hex64(fnv1a64(parent)) + "\t" +
                           tmp.file("sub/parent.toml") + "\t" + tmp.file("sub/parent.toml") + "\nenv\t" +
                           hex64(fnv1a64(env)) + "\tmaps/../maps/env1.toml\t" + tmp.file("maps/env1.toml") + "\n";
  EXPECT_EQ(chaosweep::read_attribute(tmp.file("r.h5"), "input_files"), want);
}

TEST(CliMerge, ShardsMadeWithDifferentEnvironmentFilesAreRefusedNamingTheFile) {
  TempDir tmp;
  write_file(tmp.file("env1.toml"), "obstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n");
  write_file(tmp.file("s.toml"), tiny_sweep_on(tmp.file("env1.toml")));
  const std::string sweep = "sweep " + tmp.file("s.toml") + " -q -o ";
  ASSERT_EQ(run_chaosweep(sweep + tmp.file("s0.h5") + " --shard 0/2").exit_code, 0);
  ASSERT_EQ(run_chaosweep(sweep + tmp.file("s1.h5") + " --shard 1/2").exit_code, 0);
  write_file(tmp.file("env1.toml"), "obstacles = [{ x = 0.4, y = 0.4, w = 0.3, h = 0.2 }]\n");
  ASSERT_EQ(run_chaosweep(sweep + tmp.file("edited1.h5") + " --shard 1/2").exit_code, 0);
  const auto r = run_chaosweep("merge -o " + tmp.file("m.h5") + " " + tmp.file("s0.h5") + " " + tmp.file("edited1.h5"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, tmp.file("edited1.h5") + " was made with other input files than " + tmp.file("s0.h5") + ": " +
                             tmp.file("env1.toml") + " changed (environment '" + tmp.file("env1.toml") + "')"))
      << r.err;
  EXPECT_FALSE(fs::exists(tmp.file("m.h5")) || fs::exists(tmp.file("m.h5.partial")));
  // The shards made on one map merge, and the merged file keeps the record.
  const auto ok = run_chaosweep("merge -o " + tmp.file("m.h5") + " " + tmp.file("s0.h5") + " " + tmp.file("s1.h5"));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(chaosweep::read_attribute(tmp.file("m.h5"), "inputs_hash"),
            chaosweep::read_attribute(tmp.file("s0.h5"), "inputs_hash"));
  EXPECT_TRUE(has(chaosweep::read_attribute(tmp.file("m.h5"), "input_files"), tmp.file("env1.toml")));
  // A shard that records no input files (an older chaosweep) cannot be checked: refused.
  delete_attribute(tmp.file("s1.h5"), "inputs_hash");
  const auto old = run_chaosweep("merge -o " + tmp.file("m2.h5") + " " + tmp.file("s0.h5") + " " + tmp.file("s1.h5"));
  EXPECT_EQ(old.exit_code, 2) << old.err;
  EXPECT_TRUE(has(old.err, tmp.file("s1.h5") + " does not record its input files (written by an older chaosweep)"))
      << old.err;
}
