// `chaosweep tune` and `table tune` (issue 23) as a user runs them: every
// run an ordinary row (with race_round and config_id) that table, compare
// and `run --from` read; the same file whatever --threads; kill -9 then
// --resume losing nothing; bad [tune] input refused with nothing written; a
// grid's best validated beside the tuner's choice; shards of the cases that
// merge into the whole tune.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <set>
#include <string>

#include "engine/store/h5_store.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::has;
using chaosweep::test::run_chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

namespace fs = std::filesystem;

// Two cases of cheap map-zoning runs (10 m maps) and one without parameters.
const std::string spec_text = chaosweep::test::tiny_tune_spec();

std::string shell_quoted(const std::string& s) { return "'" + s + "'"; }

// The tune of spec_text run whole into `whole`, and again into `cut`, sent
// `signal` once the first steps' rows are in cut's OUT.partial.
struct Interrupted {
  std::string spec, whole, cut;
  int exit_code = 0;
};
Interrupted interrupted_tune(const TempDir& tmp, int signal) {
  Interrupted t{tmp.file("t.toml"), tmp.file("whole.h5"), tmp.file("cut.h5")};
  const std::string partial = t.cut + ".partial";
  // The rows can be read only between the writer's steps: a tune of budget
  // 400 (~0.4 s) ended unseen in 3 of 12 tries on an idle machine, so a
  // tune that ends first is run again with four times the budget.
  for (const char* budget : {"budget = 400", "budget = 1600", "budget = 6400"}) {
    std::string longer = spec_text;
    longer.replace(longer.find("budget = 80"), 11, budget);
    write_file(t.spec, longer);
    EXPECT_EQ(run_chaosweep("tune " + shell_quoted(t.spec) + " -o " + shell_quoted(t.whole) + " -q --force").exit_code,
              0);
    fs::remove(t.cut);  // the last try's finished file
    const int pid = chaosweep::test::start_chaosweep("tune " + shell_quoted(t.spec) + " -o " + shell_quoted(t.cut) +
                                                     " -q --threads 1");
    if (!chaosweep::test::wait_for_rows(partial, 1, pid, &t.exit_code)) continue;  // it ended first
    kill(pid, signal);
    t.exit_code = chaosweep::test::wait_exit(pid);
    return t;
  }
  return t;
}

}  // namespace

TEST(CliTune, RowsAreOrdinaryRowsTheSameAtAnyThreadCountAndTableTuneReadsThem) {
  TempDir tmp;
  const std::string spec = tmp.file("t.toml"), a = tmp.file("a.h5"), b = tmp.file("b.h5");
  write_file(spec, spec_text);
  const auto r1 = run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(a) + " --threads 1");
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  EXPECT_TRUE(has(r1.out, "case open:")) << r1.out;
  EXPECT_TRUE(has(r1.out, "case plain: no parameters")) << r1.out;
  const auto r2 = run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(b) + " --threads 2 -q");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const auto cmp = run_chaosweep("compare " + shell_quoted(a) + " " + shell_quoted(b));
  EXPECT_EQ(cmp.exit_code, 0) << cmp.out << cmp.err;
  EXPECT_TRUE(has(cmp.out, "0 changed")) << cmp.out;
  // The rows: races spend at most the budget; validation on 6 fresh seeds per case.
  const auto round = read_i64_column(a, "race_round");
  const auto config = read_i64_column(a, "config_id");
  const auto seed = read_f64_column(a, "seed");
  const auto label = read_text_column(a, "label");
  std::map<std::string, int> race, validation;
  for (std::size_t r = 0; r < round.size(); ++r) {
    EXPECT_GE(config[r], 1);
    if (round[r] > 0) {
      ++race[label[r]];
      EXPECT_LT(seed[r], 1000);
    } else {
      ++validation[label[r]];
      EXPECT_GE(seed[r], 1000000);
    }
  }
  EXPECT_LE(race["open"], 80);
  EXPECT_GE(race["open"], 40);
  EXPECT_EQ(race.count("plain"), 0u);
  EXPECT_EQ(validation, (std::map<std::string, int>{{"box", 6}, {"open", 6}, {"plain", 6}}));
  EXPECT_EQ(read_attribute(a, "kind"), "tune");
  EXPECT_EQ(read_attribute(a, "runs_total"), std::to_string(round.size()));
  // table tune: a row per case; the others read the file as any result file.
  const auto t = run_chaosweep("table tune " + shell_quoted(a));
  ASSERT_EQ(t.exit_code, 0) << t.err;
  for (const char* c : {"| open |", "| box |", "| plain |", "validated CT", "6/6"})
    EXPECT_TRUE(has(t.out, c)) << c << "\n" << t.out;
  EXPECT_EQ(run_chaosweep("table summary " + shell_quoted(a)).exit_code, 0);
  const auto rerun = run_chaosweep("run --from " + shell_quoted(a) + " --run-id 5");
  EXPECT_EQ(rerun.exit_code, 0) << rerun.out << rerun.err;
  EXPECT_TRUE(has(rerun.out, "identical")) << rerun.out;
}

TEST(CliTune, KilledMidwayAndResumedItWritesTheSameFile) {
  TempDir tmp;
  const Interrupted t = interrupted_tune(tmp, SIGKILL);  // kill -9
  const std::string &spec = t.spec, &whole = t.whole, &cut = t.cut, partial = cut + ".partial";
  ASSERT_TRUE(fs::exists(partial));
  const std::int64_t had = count_rows(partial);
  const auto r = run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(cut) + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(had == 0 || has(r.out, std::to_string(had) + " already done")) << r.out;
  const auto cmp = run_chaosweep("compare " + shell_quoted(whole) + " " + shell_quoted(cut));
  EXPECT_EQ(cmp.exit_code, 0) << cmp.out;
  EXPECT_TRUE(has(cmp.out, "0 changed; 0 only in A, 0 only in B")) << cmp.out;
  EXPECT_EQ(run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(cut) + " --resume").exit_code, 0);
}

TEST(CliTune, BadTuneInputExits2AndWritesNothing) {
  TempDir tmp;
  const std::string spec = tmp.file("t.toml"), out = tmp.file("o.h5");
  std::string bad = spec_text;
  bad.replace(bad.find("max = 1 }"), 9, "max = 1000000 }");
  write_file(spec, bad);
  const auto r = run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(out));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "tune.parameters.c.max")) << r.err;
  EXPECT_TRUE(has(r.err, "1000")) << r.err;  // the allowed range
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".partial"));
  // A spec with [tune] is not swept by mistake.
  write_file(spec, spec_text);
  const auto s = run_chaosweep("sweep " + shell_quoted(spec) + " -o " + shell_quoted(out));
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_TRUE(has(s.err, "chaosweep tune")) << s.err;
  EXPECT_FALSE(fs::exists(out + ".partial"));
  const auto small = run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(out) + " --budget 4");
  EXPECT_EQ(small.exit_code, 2);
  EXPECT_TRUE(has(small.err, "--budget: must be at least 10")) << small.err;
}

TEST(CliTune, AGridsBestIsValidatedBesideTheTunersChoice) {
  TempDir tmp;
  const std::string spec = tmp.file("t.toml"), grid_spec = tmp.file("g.toml"), grid = tmp.file("g.h5"),
                    out = tmp.file("o.h5");
  write_file(spec, spec_text);
  // The grid: the same cases, a coarse c x ds_index grid on 3 seeds.
  write_file(grid_spec,
             "[fixed]\nsize = 10\nsr = 1\nic_jitter = 1e-6\nmax_time = 600\n"
             "[axes]\nseed = [0, 1, 2]\n"
             "[[part]]\nname = \"MZ\"\nfixed = { map_zoning = 1 }\n"
             "case = [ { label = \"open\", env = \"no_obstacles\" }, { label = \"box\", env = \"one_square\" } ]\n"
             "[part.axes]\nds_index = [1, 2, 3]\nc = [0.1, 0.5, 1]\n"
             "[[part]]\nname = \"plain\"\ncase = [ { label = \"plain\", env = \"no_obstacles\" } ]\n");
  ASSERT_EQ(run_chaosweep("sweep " + shell_quoted(grid_spec) + " -o " + shell_quoted(grid) + " -q").exit_code, 0);
  const auto r =
      run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(out) + " -q --grid " + shell_quoted(grid));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto config = read_i64_column(out, "config_id");
  const auto round = read_i64_column(out, "race_round");
  int beside = 0;
  for (std::size_t k = 0; k < config.size(); ++k) beside += config[k] == 0 && round[k] == 0;
  EXPECT_EQ(beside, 12);  // 6 seeds for each of the two raced cases
  const auto t = run_chaosweep("table tune " + shell_quoted(out) + " --grid " + shell_quoted(grid));
  ASSERT_EQ(t.exit_code, 0) << t.err;
  for (const char* c : {"grid's best, validated", "tuner <= grid", "grid runs", "cases", "% of the grid's"})
    EXPECT_TRUE(has(t.out, c)) << c << "\n" << t.out;
  // A grid without the case's label is named.
  const std::string other = tmp.file("other.h5");
  write_file(grid_spec, "[fixed]\nsize = 10\nlabel = \"x\"\nmax_time = 100\n[axes]\nds_index = [1, 2]\n");
  ASSERT_EQ(run_chaosweep("sweep " + shell_quoted(grid_spec) + " -o " + shell_quoted(other) + " -q").exit_code, 0);
  const auto bad = run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(tmp.file("p.h5")) + " --grid " +
                                 shell_quoted(other));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(has(bad.err, "no run labelled 'open'")) << bad.err;
}

TEST(CliTune, SigintFinishesTheRunsInFlightExits130AndResumes) {
  TempDir tmp;
  const Interrupted t = interrupted_tune(tmp, SIGINT);
  const std::string &spec = t.spec, &whole = t.whole, &cut = t.cut;
  const int code = t.exit_code;
  if (code == 0) GTEST_SKIP() << "the tune finished before the signal";
  EXPECT_EQ(code, 130);
  EXPECT_FALSE(fs::exists(cut));
  ASSERT_EQ(run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(cut) + " --resume -q").exit_code, 0);
  const auto cmp = run_chaosweep("compare " + shell_quoted(whole) + " " + shell_quoted(cut));
  EXPECT_TRUE(has(cmp.out, "0 changed; 0 only in A, 0 only in B")) << cmp.out;
}

// --shard K/N races the cases i with i % N == K; merge joins the shards into
// the whole tune's rows, and refuses a missing, unfinished or foreign shard.
TEST(CliTune, ShardsOfTheCasesMergeIntoTheWholeTune) {
  TempDir tmp;
  const std::string spec = tmp.file("t.toml"), whole = tmp.file("whole.h5"), merged = tmp.file("merged.h5");
  write_file(spec, spec_text);
  ASSERT_EQ(run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(whole) + " -q").exit_code, 0);
  std::vector<std::string> shard(2);
  for (int k = 0; k < 2; ++k) {
    shard[k] = tmp.file("s" + std::to_string(k) + ".h5");
    const auto r = run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(shard[k]) + " --shard " +
                                 std::to_string(k) + "/2 --threads " + std::to_string(k + 1));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "shard " + std::to_string(k) + "/2")) << r.out;
    EXPECT_EQ(read_attribute(shard[k], "shard"), std::to_string(k) + "/2");
  }
  const std::vector<std::string> labels = read_text_column(shard[0], "label");
  const std::set<std::string> first(labels.begin(), labels.end());
  EXPECT_EQ(first, (std::set<std::string>{"open", "plain"}));  // cases 0 and 2
  // One shard alone: nothing written, the missing one named.
  const auto one = run_chaosweep("merge -o " + shell_quoted(merged) + " " + shell_quoted(shard[1]));
  EXPECT_EQ(one.exit_code, 1) << one.err;
  EXPECT_TRUE(has(one.out, "missing shards 0 of 2")) << one.out;
  EXPECT_TRUE(has(one.out, "chaosweep tune SPEC -o OUT --shard 0/2 --resume")) << one.out;
  EXPECT_FALSE(fs::exists(merged));
  const auto m =
      run_chaosweep("merge -o " + shell_quoted(merged) + " " + shell_quoted(shard[1]) + " " + shell_quoted(shard[0]));
  ASSERT_EQ(m.exit_code, 0) << m.out << m.err;
  const auto cmp = run_chaosweep("compare " + shell_quoted(whole) + " " + shell_quoted(merged));
  EXPECT_EQ(cmp.exit_code, 0) << cmp.out << cmp.err;
  EXPECT_TRUE(has(cmp.out, "0 changed; 0 only in A, 0 only in B")) << cmp.out;
  EXPECT_EQ(read_attribute(merged, "runs_total"), std::to_string(count_rows(whole)));
  EXPECT_EQ(read_attribute(merged, "kind"), "tune");
  const auto t = run_chaosweep("table tune " + shell_quoted(merged));
  EXPECT_EQ(t.exit_code, 0) << t.err;
  EXPECT_EQ(t.out, run_chaosweep("table tune " + shell_quoted(whole)).out);
  // A sweep's shard is not a tune's; a tune's whole file is not a shard of 2.
  const std::string sweep_spec = tmp.file("s.toml"), sweep = tmp.file("sweep.h5");
  write_file(sweep_spec, chaosweep::test::small_spec_18_runs("other"));
  ASSERT_EQ(run_chaosweep("sweep " + shell_quoted(sweep_spec) + " -q --shard 1/2 -o " + shell_quoted(sweep)).exit_code,
            0);
  const auto mixed = run_chaosweep("merge -o " + shell_quoted(tmp.file("x.h5")) + " " + shell_quoted(shard[0]) + " " +
                                   shell_quoted(sweep));
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_TRUE(has(mixed.err, "not both a tune's shards")) << mixed.err;
  const auto other = run_chaosweep("merge -o " + shell_quoted(tmp.file("x.h5")) + " " + shell_quoted(shard[0]) + " " +
                                   shell_quoted(whole));
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_TRUE(has(other.err, "shards")) << other.err;
  EXPECT_FALSE(fs::exists(tmp.file("x.h5")));
  // More shards than cases: each shard races whole cases.
  const auto many =
      run_chaosweep("tune " + shell_quoted(spec) + " -o " + shell_quoted(tmp.file("y.h5")) + " --shard 0/4");
  EXPECT_EQ(many.exit_code, 2);
  EXPECT_TRUE(has(many.err, "--shard: 0/4")) << many.err;
  EXPECT_TRUE(has(many.err, "give N in [1, 3]")) << many.err;
  EXPECT_FALSE(fs::exists(tmp.file("y.h5.partial")));
}

// An unfinished shard (its OUT.partial, given by hand) is refused by name.
TEST(CliTune, AnUnfinishedTuneShardIsNotMerged) {
  TempDir tmp;
  const Interrupted t = interrupted_tune(tmp, SIGKILL);
  const std::string partial = t.cut + ".partial";
  ASSERT_TRUE(fs::exists(partial));
  const auto m = run_chaosweep("merge -o " + shell_quoted(tmp.file("m.h5")) + " " + shell_quoted(partial));
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_TRUE(has(m.err, "is not a finished tune")) << m.err;
  EXPECT_TRUE(has(m.err, "--resume")) << m.err;
  EXPECT_FALSE(fs::exists(tmp.file("m.h5")));
}
