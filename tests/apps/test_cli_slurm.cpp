// `chaosweep slurm`: what goes into a job script. Values are checked against
// the forms SLURM accepts (exit 2 naming the flag, nothing written), paths are
// shell-quoted, --tasks is bounded by the run count, and the merge script does
// not list the shards. The scripts are run here with bash as SLURM would run
// them (tests/slurm_integration.sh submits them to a real SLURM).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "apps/chaosweep/slurm_values.hpp"
#include "tests/support/test_util.hpp"

namespace {

using chaosweep::shell_quote;
using chaosweep::test::read_file;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;
namespace fs = std::filesystem;

const std::string spec_18_runs = chaosweep::test::small_spec_18_runs("slurm-small");

// Runs `script` with bash in `dir`, with `env` (NAME=VALUE ...) set; exit code.
int run_script(const std::string& script, const std::string& env, const std::string& dir) {
  const std::string cmd = "cd " + shell_quote(dir) + " && env " + env + " bash " + shell_quote(script) + " >" +
                          shell_quote(dir + "/script.log") + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(CliSlurm, InjectionStringsAreRefusedNamingTheFlagAndNothingIsWritten) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), spec_18_runs);
  struct Case {
    std::string flag, value, says;
  };
  const std::vector<Case> cases{
      {"--partition", "batch\necho INJECTED > f", "is not a SLURM partition"},
      {"--partition", "batch,", "is not a SLURM partition"},
      {"--time", "02:00; rm -rf /", "is not a SLURM time"},
      {"--time", "$(id)", "is not a SLURM time"},
      {"--mem", "$(id)", "is not a SLURM memory size"},
      {"--mem", "4G\n#SBATCH --uid=0", "is not a SLURM memory size"},
      {"--account", "proj`id`", "is not a SLURM account"},
      {"--job-name", "a b", "is not a SLURM job name"},
      {"-o", tmp.file("run dir"), "cannot be written into an #SBATCH line"},
      {"-o", tmp.file("run\nls"), "cannot be written into an #SBATCH line"},
      {"-o", tmp.file("run_%j"), "cannot be written into an #SBATCH line"},
  };
  for (const Case& c : cases) {
    const std::string dir = c.flag == "-o" ? c.value : tmp.file("run");
    std::string args = "slurm " + tmp.file("s.toml") + " --tasks 2 -o " + shell_quote(dir);
    if (c.flag != "-o") args += " " + c.flag + " " + shell_quote(c.value);
    const auto r = run_chaosweep(args);
    EXPECT_EQ(r.exit_code, 2) << c.flag << " " << c.value;
    EXPECT_NE(r.err.find("chaosweep slurm: " + c.flag + ": '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line, control characters escaped: " << r.err;
    EXPECT_FALSE(fs::exists(dir)) << c.flag << ": nothing may be written";
  }
  EXPECT_FALSE(fs::exists(tmp.file("f")));
}

TEST(CliSlurm, TheFormsSlurmAcceptsGoIntoTheScriptAsGiven) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), spec_18_runs);
  const std::vector<std::pair<std::string, std::string>> accepted{
      {"--time", "30"},         {"--time", "30:15"},         {"--time", "02:00:00"},
      {"--time", "1-12"},       {"--time", "1-12:30"},       {"--time", "1-12:30:00"},
      {"--time", "UNLIMITED"},  {"--mem", "4096"},           {"--mem", "4G"},
      {"--mem", "500m"},        {"--partition", "batch"},    {"--partition", "gpu-a100,cpu.long_1"},
      {"--account", "proj_42"}, {"--job-name", "fig6.run-2"}};
  for (const auto& [flag, value] : accepted) {
    const auto r = run_chaosweep("slurm " + tmp.file("s.toml") + " --tasks 2 --force -o " + tmp.file("run") + " " +
                                 flag + " " + shell_quote(value));
    ASSERT_EQ(r.exit_code, 0) << flag << " " << value << ": " << r.err;
    const std::string directive = "#SBATCH " + flag + "=" + value + (flag == "--job-name" ? "" : "\n");
    EXPECT_NE(read_file(tmp.file("run/sweep.sbatch")).find(directive), std::string::npos) << directive;
  }
}

TEST(CliSlurm, ASpecNameIsMadeAJobNameNotCopied) {
  TempDir tmp;
  std::string spec = spec_18_runs;
  spec.replace(spec.find("slurm-small"), 11, "x; echo INJECTED $(id)");
  write_file(tmp.file("s.toml"), spec);
  const auto r = run_chaosweep("slurm " + tmp.file("s.toml") + " --tasks 2 -o " + tmp.file("run"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = read_file(tmp.file("run/sweep.sbatch"));
  EXPECT_NE(script.find("#SBATCH --job-name=chaosweep-x__echo_INJECTED___id_\n"), std::string::npos) << script;
  EXPECT_EQ(script.find("echo INJECTED"), std::string::npos) << script;
  EXPECT_EQ(chaosweep::to_slurm_job_name("a\nb c"), "a_b_c");
}

TEST(CliSlurm, TasksAreBoundedByTheRunCount) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), spec_18_runs);
  const auto big = run_chaosweep("slurm " + tmp.file("s.toml") + " --tasks 1000000 -o " + tmp.file("run"));
  EXPECT_EQ(big.exit_code, 2);
  EXPECT_NE(big.err.find("--tasks: 1000000 is more than the spec's 18 runs"), std::string::npos) << big.err;
  EXPECT_NE(big.err.find("give --tasks in [1, 18]"), std::string::npos) << big.err;
  EXPECT_FALSE(fs::exists(tmp.file("run")));
  EXPECT_EQ(run_chaosweep("slurm " + tmp.file("s.toml") + " --tasks 19 -o " + tmp.file("run")).exit_code, 2);
  EXPECT_EQ(run_chaosweep("slurm " + tmp.file("s.toml") + " --tasks 18 -o " + tmp.file("run")).exit_code, 0);
}

// Every task's script and then the merge script, run by bash as SLURM would,
// from a spec whose path holds quotes, '$(...)' and spaces: the merged file
// equals a single-machine sweep, and the merge script names no shard.
TEST(CliSlurm, TheScriptsRunWithQuotedPathsAndTheMergeListsNoShard) {
  TempDir tmp;
  const std::string odd = tmp.file("it's a \"spec\" $(touch pwned) `touch pwned2`");
  fs::create_directories(odd);
  write_file(odd + "/s.toml", spec_18_runs);
  const int tasks = 18;  // one run each: the most the spec allows
  const auto w = run_chaosweep("slurm " + shell_quote(odd + "/s.toml") + " --tasks " + std::to_string(tasks) + " -o " +
                               tmp.file("run"));
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const std::string merge = read_file(tmp.file("run/merge.sbatch"));
  EXPECT_EQ(merge.find("shard_"), std::string::npos) << merge;
  EXPECT_LT(merge.size(), 2000u);
  for (int k = 0; k < tasks; ++k)
    ASSERT_EQ(run_script(tmp.file("run/sweep.sbatch"),
                         "SLURM_ARRAY_TASK_ID=" + std::to_string(k) + " SLURM_CPUS_PER_TASK=1", tmp.path().string()),
              0)
        << read_file(tmp.file("script.log"));
  ASSERT_EQ(run_script(tmp.file("run/merge.sbatch"), "", tmp.path().string()), 0) << read_file(tmp.file("script.log"));
  const auto single = run_chaosweep("sweep " + shell_quote(odd + "/s.toml") + " -q -o " + tmp.file("single.h5"));
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const auto cmp = run_chaosweep("compare " + tmp.file("run/results.h5") + " " + tmp.file("single.h5"));
  EXPECT_EQ(cmp.exit_code, 0) << cmp.out << cmp.err;
  EXPECT_FALSE(fs::exists(tmp.file("pwned")));
  EXPECT_FALSE(fs::exists(tmp.file("pwned2")));
}

// An environment named by a relative path is found from the working
// directory: slurm checks it from the directory it runs in, and the tasks'
// script runs there too, wherever the job starts (sbatch starts it where it
// was submitted from). A map slurm cannot find is refused before anything is
// written (every task would have failed).
TEST(CliSlurm, ARelativeEnvironmentPathIsFoundFromTheDirectorySlurmRanIn) {
  TempDir tmp;
  fs::create_directories(tmp.file("work/maps"));
  fs::create_directories(tmp.file("specs"));
  write_file(tmp.file("work/maps/env1.toml"), "obstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n");
  write_file(tmp.file("specs/s.toml"),
             "[fixed]\nenv = \"maps/env1.toml\"\nsize = 10\nsr = 2\nmax_time = 5\n[axes]\nA = [0.4, 0.5, 0.6]\n");
  const auto lost =
      run_chaosweep("slurm specs/s.toml --tasks 3 -o run", "cd " + shell_quote(tmp.path().string()) + " &&");
  EXPECT_EQ(lost.exit_code, 2);
  EXPECT_NE(lost.err.find("environment 'maps/env1.toml' not found"), std::string::npos) << lost.err;
  EXPECT_FALSE(fs::exists(tmp.file("run")));
  const auto w =
      run_chaosweep("slurm ../specs/s.toml --tasks 3 -o ../run", "cd " + shell_quote(tmp.file("work")) + " &&");
  ASSERT_EQ(w.exit_code, 0) << w.err;
  for (int k = 0; k < 3; ++k)
    ASSERT_EQ(run_script(tmp.file("run/sweep.sbatch"), "SLURM_ARRAY_TASK_ID=" + std::to_string(k), tmp.path().string()),
              0)
        << read_file(tmp.file("script.log"));
  ASSERT_EQ(run_script(tmp.file("run/merge.sbatch"), "", tmp.path().string()), 0) << read_file(tmp.file("script.log"));
  const auto single =
      run_chaosweep("sweep ../specs/s.toml -q -o ../single.h5", "cd " + shell_quote(tmp.file("work")) + " &&");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const auto cmp = run_chaosweep("compare " + tmp.file("run/results.h5") + " " + tmp.file("single.h5"));
  EXPECT_EQ(cmp.exit_code, 0) << cmp.out << cmp.err;
  // Where that directory is gone (a node that cannot see it), a spec of
  // absolute paths still runs.
  fs::create_directories(tmp.file("gone"));
  write_file(tmp.file("specs/abs.toml"), "[fixed]\nenv = \"" + tmp.file("work/maps/env1.toml") +
                                             "\"\nsize = 10\nsr = 2\nmax_time = 5\n[axes]\nA = [0.4, 0.5]\n");
  ASSERT_EQ(run_chaosweep("slurm ../specs/abs.toml --tasks 1 -o ../run2", "cd " + shell_quote(tmp.file("gone")) + " &&")
                .exit_code,
            0);
  fs::remove_all(tmp.file("gone"));
  EXPECT_EQ(run_script(tmp.file("run2/sweep.sbatch"), "SLURM_ARRAY_TASK_ID=0", tmp.path().string()), 0)
      << read_file(tmp.file("script.log"));
  EXPECT_TRUE(fs::exists(tmp.file("run2/shard_0.h5")));
}

TEST(CliMerge, SlurmDirMergesTheShardsOfTheDirectoryAndNamesAMissingOne) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), spec_18_runs);
  ASSERT_EQ(run_chaosweep("slurm " + tmp.file("s.toml") + " --tasks 3 -o " + tmp.file("run")).exit_code, 0);
  const auto none = run_chaosweep("merge -o " + tmp.file("m.h5") + " --slurm-dir " + tmp.file("run"));
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("holds no shard file yet"), std::string::npos) << none.err;
  for (int k : {0, 2})
    ASSERT_EQ(run_chaosweep("sweep " + tmp.file("s.toml") + " -q --shard " + std::to_string(k) + "/3 -o " +
                            tmp.file("run/shard_" + std::to_string(k) + ".h5"))
                  .exit_code,
              0);
  const auto partial = run_chaosweep("merge -o " + tmp.file("m.h5") + " --slurm-dir " + tmp.file("run"));
  EXPECT_EQ(partial.exit_code, 1);
  EXPECT_NE(partial.out.find("re-run shards 1 of 3"), std::string::npos) << partial.out;
  EXPECT_FALSE(fs::exists(tmp.file("m.h5")));
  const auto both = run_chaosweep("merge -o " + tmp.file("m.h5") + " --slurm-dir " + tmp.file("run") + " " +
                                  tmp.file("run/shard_0.h5"));
  EXPECT_EQ(both.exit_code, 2) << "a list and --slurm-dir exclude each other";
}

TEST(SlurmValues, ShellQuoteGivesBashBackTheSameWord) {
  TempDir tmp;
  for (const std::string s : {"plain", "it's", "a b", "$(id)", "`id`", "x\ny", "'''", "\\\"", ""}) {
    const std::string out = tmp.file("out");
    const std::string cmd = "printf %s " + shell_quote(s) + " > " + shell_quote(out);
    ASSERT_EQ(std::system(cmd.c_str()), 0) << s;
    EXPECT_EQ(read_file(out), s);
  }
}

// A tune spec's tasks each race their shard of the cases (`chaosweep tune
// --shard K/N`); the merge script joins them into the whole tune's rows, and
// status counts a finished tune shard as finished.
TEST(CliSlurm, ATuneSpecsTasksRaceItsCasesAndTheMergeJoinsThem) {
  TempDir tmp;
  write_file(tmp.file("t.toml"), chaosweep::test::tiny_tune_spec());
  const auto many = run_chaosweep("slurm " + tmp.file("t.toml") + " --tasks 4 -o " + tmp.file("run"));
  EXPECT_EQ(many.exit_code, 2);
  EXPECT_NE(many.err.find("more than the tune's 3 cases"), std::string::npos) << many.err;
  EXPECT_FALSE(fs::exists(tmp.file("run")));
  const auto w = run_chaosweep("slurm " + tmp.file("t.toml") + " --tasks 2 -o " + tmp.file("run"));
  ASSERT_EQ(w.exit_code, 0) << w.err;
  EXPECT_NE(w.out.find("a tune of at most"), std::string::npos) << w.out;
  EXPECT_NE(read_file(tmp.file("run/sweep.sbatch")).find(" tune "), std::string::npos);
  for (int k = 0; k < 2; ++k)
    ASSERT_EQ(run_script(tmp.file("run/sweep.sbatch"),
                         "SLURM_ARRAY_TASK_ID=" + std::to_string(k) + " SLURM_CPUS_PER_TASK=1", tmp.path().string()),
              0)
        << read_file(tmp.file("script.log"));
  const auto st = run_chaosweep("status " + tmp.file("run"));
  EXPECT_EQ(st.exit_code, 0) << st.out << st.err;
  EXPECT_NE(st.out.find("tune '"), std::string::npos) << st.out;
  EXPECT_NE(st.out.find("finished 2: 0,1"), std::string::npos) << st.out;
  ASSERT_EQ(run_script(tmp.file("run/merge.sbatch"), "", tmp.path().string()), 0) << read_file(tmp.file("script.log"));
  ASSERT_EQ(run_chaosweep("tune " + tmp.file("t.toml") + " -q -o " + tmp.file("single.h5")).exit_code, 0);
  const auto cmp = run_chaosweep("compare " + tmp.file("run/results.h5") + " " + tmp.file("single.h5"));
  EXPECT_EQ(cmp.exit_code, 0) << cmp.out << cmp.err;
  EXPECT_NE(cmp.out.find("0 changed; 0 only in A, 0 only in B"), std::string::npos) << cmp.out;
}
