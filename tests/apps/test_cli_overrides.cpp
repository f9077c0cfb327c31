// --set KEY=VALUE on plan, sweep and slurm: the changed spec is what runs, is
// stored, is checked on --resume, and reaches every SLURM task quoted.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "apps/chaosweep/slurm_values.hpp"
#include "engine/store/h5_store.hpp"
#include "tests/support/test_util.hpp"

namespace {

using chaosweep::shell_quote;
using chaosweep::test::read_file;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

const std::string spec_18_runs = chaosweep::test::small_spec_18_runs("set-small");

}  // namespace

TEST(CliSet, ASweepRunsStoresAndResumesTheChangedSpec) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), spec_18_runs);
  const std::string sets = " --set sr=3 --set 'A=[0.45, 0.55]'";
  const auto plan = run_chaosweep("plan " + tmp.file("s.toml") + sets);
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  EXPECT_NE(plan.out.find("runs        12  (2 x 2 x 3)"), std::string::npos) << plan.out;
  EXPECT_NE(plan.out.find("--set       sr=3 A=[0.45, 0.55]"), std::string::npos) << plan.out;
  const auto estimate = run_chaosweep("plan " + tmp.file("s.toml") + sets + " --estimate --calibration 8 --threads 1");
  ASSERT_EQ(estimate.exit_code, 0) << estimate.err;
  EXPECT_NE(estimate.out.find("wall on 1 threads (~95% interval "), std::string::npos) << estimate.out;
  EXPECT_NE(estimate.out.find("from 8 runs drawn across the spec"), std::string::npos) << estimate.out;
  const std::string args = "sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("r.h5");
  ASSERT_EQ(run_chaosweep(args + sets).exit_code, 0);
  EXPECT_EQ(chaosweep::read_f64_column(tmp.file("r.h5"), "sr"), std::vector<double>(12, 3.0));
  const auto a = chaosweep::read_f64_column(tmp.file("r.h5"), "A");
  EXPECT_EQ(a.front(), 0.45);
  EXPECT_EQ(a.back(), 0.55);
  const std::string spec = chaosweep::read_attribute(tmp.file("r.h5"), "spec");
  EXPECT_NE(spec.find("sr = 3\n"), std::string::npos) << spec;
  EXPECT_NE(spec.find("# chaosweep --set sr=3 A=[0.45, 0.55]\n"), std::string::npos) << spec;
  // The stored spec is a spec: swept as a file it gives the same rows.
  write_file(tmp.file("stored.toml"), spec);
  ASSERT_EQ(run_chaosweep("sweep " + tmp.file("stored.toml") + " -q -o " + tmp.file("again.h5")).exit_code, 0);
  const auto same = run_chaosweep("compare " + tmp.file("r.h5") + " " + tmp.file("again.h5"));
  EXPECT_EQ(same.exit_code, 0) << same.out << same.err;
  // --resume holds the file to the same flags.
  EXPECT_EQ(run_chaosweep(args + sets + " --resume").exit_code, 0);
  for (const std::string& other : {std::string(" --set sr=4 --set 'A=[0.45, 0.55]'"), std::string()}) {
    const auto refused = run_chaosweep(args + other + " --resume");
    EXPECT_EQ(refused.exit_code, 2) << other << ": " << refused.err;
  }
  // A bad flag is the spec's error, named, and nothing is written.
  const auto bad = run_chaosweep("sweep " + tmp.file("s.toml") + " -q -o " + tmp.file("bad.h5") + " --set sr=-1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("fixed.sr: sr = -1 is out of range"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("(the spec with --set sr=-1)"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.file("bad.h5.partial")));
}

TEST(CliSet, EveryTaskOfASlurmSweepRunsTheChangedSpecWithTheValuesQuoted) {
  TempDir tmp;
  write_file(tmp.file("s.toml"), spec_18_runs);
  // A value a shell would expand, were it not quoted: it must reach the spec as text.
  const std::string sets = " --set sr=3 --set " + shell_quote("label=\"$(touch pwned) `touch pwned2` it's\"");
  const auto w = run_chaosweep("slurm " + tmp.file("s.toml") + " --tasks 2 -o " + tmp.file("run") + sets);
  ASSERT_EQ(w.exit_code, 0) << w.err;
  for (int k = 0; k < 2; ++k) {
    const std::string cmd = "cd " + shell_quote(tmp.path().string()) +
                            " && env SLURM_ARRAY_TASK_ID=" + std::to_string(k) + " SLURM_CPUS_PER_TASK=1 bash " +
                            tmp.file("run/sweep.sbatch") + " >" + tmp.file("script.log") + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_file(tmp.file("script.log"));
  }
  ASSERT_EQ(run_chaosweep("merge -o " + tmp.file("m.h5") + " --slurm-dir " + tmp.file("run")).exit_code, 0);
  EXPECT_EQ(chaosweep::read_f64_column(tmp.file("m.h5"), "sr"), std::vector<double>(18, 3.0));
  const auto labels = chaosweep::read_text_column(tmp.file("m.h5"), "label");
  EXPECT_EQ(labels.front(), "$(touch pwned) `touch pwned2` it's");
  EXPECT_FALSE(std::filesystem::exists(tmp.file("pwned")));
  EXPECT_FALSE(std::filesystem::exists(tmp.file("pwned2")));
}
