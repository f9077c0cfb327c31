// The tuner (engine/tune, issue 23): the [tune] section's checks, one case's
// iterated race on costs made up here (so what it must find is known), and
// the runner over real runs: independent of the evaluator and its threads,
// and a replay from stored rows that runs only what they lack.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "engine/rows/run_hash.hpp"
#include "engine/run/serial_batch_evaluator.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/tune/race.hpp"
#include "engine/tune/tune_runner.hpp"
#include "kernels/math/splitmix.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::has;

namespace {

const std::string two_parts =
    "[fixed]\nmax_time = 400\nsize = 10\nsr = 1\nic_jitter = 1e-6\n"
    "[[part]]\nname = \"MZ\"\nfixed = { map_zoning = 1 }\n"
    "case = [ { label = \"open\", env = \"no_obstacles\" }, { label = \"box\", env = \"one_square\" } ]\n"
    "[[part]]\nname = \"plain\"\ncase = [ { label = \"plain\", env = \"no_obstacles\" } ]\n";

const std::string tune_ok =
    "[tune]\nbudget = 60\nseed = 3\nvalidation_seeds = 4\n"
    "[tune.parameters]\nds_index = [1, 2, 3]\nc = { min = 0.05, max = 1 }\n"
    "[tune.part.MZ]\nparameters = [\"ds_index\", \"c\"]\n"
    "[tune.part.plain]\nparameters = []\n";

TuneSpec parse(const std::string& text) { return tune_spec_of(parse_sweep_spec(text, "t.toml"), "t.toml"); }

std::string tune_error(const std::string& text) {
  try {
    parse(text);
  } catch (const SpecError& e) {
    return e.what();
  }
  return "";
}

// A race over one real x in [0, 1] and a choice k in {0, 1, 2}: the cost is
// (x - 0.3)^2 * 1000 + 50 k + noise of the seed, so the best is k = 0, x = 0.3.
double made_up_cost(const Race& r, const RaceEvaluation& e) {
  const Candidate& c = r.candidate(e.config);
  std::uint64_t s = std::uint64_t(e.seed) * 7919;
  const double noise = 20 * uniform01(s);
  return 1000 * (c.values[0] - 0.3) * (c.values[0] - 0.3) + 50 * c.values[1] + noise;
}

Race made_up_race(std::int64_t budget, std::uint64_t seed, RaceTest test = RaceTest::friedman) {
  TuneSpec settings;
  settings.test = test;
  TuneParameter x{"c", true, 0.0, 1.0, {}};
  TuneParameter k{"ds_index", false, 0, 0, {1.0, 2.0, 3.0}};
  return Race({x, k}, budget, settings, seed);
}

struct RaceLog {
  std::vector<RaceEvaluation> all;
};

RaceLog run_made_up(Race& r) {
  RaceLog log;
  for (std::vector<RaceEvaluation> step = r.next(); !step.empty(); step = r.next()) {
    std::vector<double> costs;
    for (const RaceEvaluation& e : step) costs.push_back(made_up_cost(r, e));
    log.all.insert(log.all.end(), step.begin(), step.end());
    r.take(costs);
  }
  return log;
}

}  // namespace

TEST(TuneSpec, ReadsTheParametersThePartsSearchAndTheirBudgets) {
  const TuneSpec t = parse(two_parts + tune_ok);
  // In name order (TOML tables are unordered), whatever the file's order.
  ASSERT_EQ(t.parameters.size(), 2u);
  EXPECT_EQ(t.parameters[0].key, "c");
  EXPECT_TRUE(t.parameters[0].real);
  EXPECT_EQ(t.parameters[0].lo, 0.05);
  EXPECT_EQ(t.parameters[1].key, "ds_index");
  EXPECT_FALSE(t.parameters[1].real);
  ASSERT_EQ(t.cases.size(), 3u);
  EXPECT_EQ(t.cases[0].run.label, "open");
  EXPECT_EQ(t.cases[0].parameters.size(), 2u);
  EXPECT_EQ(t.cases[0].budget, 60);
  EXPECT_TRUE(t.cases[2].parameters.empty());
  EXPECT_EQ(t.validation_seeds, 4);
  EXPECT_EQ(t.seed, 3u);
  // --budget replaces every case's.
  EXPECT_EQ(tune_spec_of(parse_sweep_spec(two_parts + tune_ok, "t"), "t", 20).cases[1].budget, 20);
  // The run of a configuration: its values, and the seed.
  const RunSpec r = tune_run(t, t.cases[0], {2, 0.25}, 7);  // the part's order: ds_index, c
  EXPECT_EQ(r.params.ds_index, 3);
  EXPECT_EQ(r.params.c, 0.25);
  EXPECT_EQ(r.params.seed, 7);
  EXPECT_EQ(r.label, "open");
}

TEST(TuneSpec, BadInputNamesTheKeyAndWhatItMayBe) {
  const std::string parts = two_parts;
  const std::string params = "[tune.parameters]\nds_index = [1, 2, 3]\nc = { min = 0.05, max = 1 }\n";
  const std::string part_lists = "[tune.part.MZ]\nparameters = [\"c\"]\n[tune.part.plain]\nparameters = []\n";
  struct Case {
    std::string text, expect;
  };
  const std::vector<Case> cases = {
      {parts + "[tune]\nbudget = 60\n" + part_lists, "tune.parameters: is missing"},
      {parts + "[tune]\nbudget = 60\nbudgte = 3\n" + params + part_lists, "unknown key 'budgte'"},
      {parts + "[tune]\n" + params + part_lists, "tune.budget: is missing"},
      {parts + "[tune]\nbudget = 3\n" + params + part_lists, "tune.budget: must be at least 10"},
      {parts + "[tune]\nbudget = 60\nconfidence = 1.5\n" + params + part_lists,
       "tune.confidence: must be a number in [0.5, 0.999]"},
      {parts + "[tune]\nbudget = 60\ntest = \"t-test\"\n" + params + part_lists,
       "tune.test: must be \"friedman\" or \"wilcoxon\""},
      {parts + "[tune]\nbudget = 60\n[tune.parameters]\nc = { min = 1, max = 0.5 }\n" + part_lists,
       "tune.parameters.c: min must be below max"},
      {parts + "[tune]\nbudget = 60\n[tune.parameters]\nc = { min = 0.05, max = 1 }\ndc = { min = 0.5, max = 1.5 }\n" +
           part_lists,
       "tune.parameters.dc.max: "},
      {parts + "[tune]\nbudget = 60\n[tune.parameters]\nds_index = [1, 4]\n" + part_lists,
       "tune.parameters.ds_index[1]"},
      {parts + "[tune]\nbudget = 60\n[tune.parameters]\nds_index = [1, 1]\n" + part_lists, "is listed twice"},
      {parts + "[tune]\nbudget = 60\n[tune.parameters]\nseed = [1, 2]\n" + part_lists, "'seed' cannot be searched"},
      {parts + "[tune]\nbudget = 60\n[tune.parameters]\nmap_zoning = [0, 1]\n" + part_lists,
       "is set by the spec's axes or a part"},
      {parts + "[tune]\nbudget = 60\n" + params +
           "[tune.part.MZ]\nparameters = [\"f\"]\n[tune.part.plain]\nparameters = []\n",
       "tune.part.MZ.parameters[0]: 'f' is not in tune.parameters"},
      {parts + "[tune]\nbudget = 60\n" + params + "[tune.part.MZ]\nparameters = [\"c\"]\n",
       "has no entry for part 'plain'"},
      {parts + "[tune]\nbudget = 60\n" + params + part_lists + "[tune.part.other]\nparameters = []\n",
       "tune.part.other: is not a [[part]] of the spec"},
      {parts + "[axes]\nseed = [1, 2]\n[tune]\nbudget = 60\n" + params + part_lists, "the tuner sets each run's seed"},
      {parts, "has no [tune] section"},
  };
  for (const Case& c : cases)
    EXPECT_TRUE(has(tune_error(c.text), c.expect)) << c.expect << "\n got: " << tune_error(c.text);
  EXPECT_EQ(tune_error(two_parts + tune_ok), "");
}

TEST(Race, FindsTheMadeUpOptimumWithinItsBudget) {
  Race r = made_up_race(400, 1);
  const RaceLog log = run_made_up(r);
  EXPECT_TRUE(r.done());
  EXPECT_LE(r.spent(), 400);
  EXPECT_GE(r.spent(), 300);  // the budget is used, not left over
  EXPECT_EQ(std::int64_t(log.all.size()), r.spent());
  ASSERT_NE(r.best(), 0);
  const Candidate& best = r.candidate(r.best());
  EXPECT_EQ(best.values[1], 0.0);
  EXPECT_NEAR(best.values[0], 0.3, 0.08);
  EXPECT_GE(r.iteration(), 2);
  // New configurations came from the elites: later ones sit nearer the optimum.
  double first = 0, last = 0;
  int n_first = 0, n_last = 0, newest = 0;
  for (const Candidate& c : r.candidates()) newest = std::max(newest, c.born);
  EXPECT_GE(newest, 2);
  for (const Candidate& c : r.candidates()) {
    const double d = std::abs(c.values[0] - 0.3);
    if (c.born == 1) first += d, ++n_first;
    if (c.born == newest) last += d, ++n_last;
  }
  ASSERT_GT(n_first, 0);
  ASSERT_GT(n_last, 0);
  EXPECT_LT(last / n_last, first / n_first / 2);
  // A sampled real has 4 significant digits: the printed value is the value.
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", best.values[0]);
  EXPECT_EQ(std::strtod(buf, nullptr), best.values[0]);
}

// Where the cost falls all the way to a range's end (as CT does towards c = 1
// on some Table 1 maps), the race must be able to choose the end itself: a
// child drawn beyond it lands on it, rather than being drawn again inside.
TEST(Race, ReachesAnOptimumAtTheEndOfARange) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    TuneSpec settings;
    Race r({TuneParameter{"c", true, 0.05, 1.0, {}}}, 300, settings, seed);
    for (std::vector<RaceEvaluation> step = r.next(); !step.empty(); step = r.next()) {
      std::vector<double> costs;
      for (const RaceEvaluation& e : step) {
        std::uint64_t s = std::uint64_t(e.seed) * 7919;
        costs.push_back(100 * (1 - r.candidate(e.config).values[0]) + 5 * uniform01(s));
      }
      r.take(costs);
    }
    ASSERT_NE(r.best(), 0);
    EXPECT_EQ(r.candidate(r.best()).values[0], 1.0) << "seed " << seed;
    for (const Candidate& c : r.candidates()) {
      EXPECT_GE(c.values[0], 0.05);
      EXPECT_LE(c.values[0], 1.0);
    }
  }
}

TEST(Race, EveryRaceRunsItsConfigurationsOnTheSameSeedsFromZeroAndNeverTwice) {
  Race r = made_up_race(300, 5);
  const RaceLog log = run_made_up(r);
  std::set<std::pair<std::int64_t, std::int64_t>> seen;
  std::map<std::int64_t, std::int64_t> next_seed;
  for (const RaceEvaluation& e : log.all) {
    EXPECT_TRUE(seen.insert({e.config, e.seed}).second) << "config " << e.config << " seed " << e.seed << " twice";
    EXPECT_EQ(e.seed, next_seed[e.config]) << "config " << e.config;  // 0, 1, 2, ... in order
    next_seed[e.config] = e.seed + 1;
  }
}

TEST(Race, IsAFunctionOfItsSeedAndCosts) {
  Race a = made_up_race(300, 9), b = made_up_race(300, 9), c = made_up_race(300, 10);
  const RaceLog la = run_made_up(a), lb = run_made_up(b), lc = run_made_up(c);
  ASSERT_EQ(la.all.size(), lb.all.size());
  for (std::size_t k = 0; k < la.all.size(); ++k) {
    EXPECT_EQ(la.all[k].config, lb.all[k].config);
    EXPECT_EQ(la.all[k].seed, lb.all[k].seed);
  }
  EXPECT_EQ(a.candidate(a.best()).values, b.candidate(b.best()).values);
  EXPECT_NE(a.candidates()[0].values, c.candidates()[0].values);  // another seed, another sample
}

TEST(Race, DropsAConfigurationTheTestShowsWorse) {
  TuneSpec settings;
  TuneParameter k{"ds_index", false, 0, 0, {1.0, 2.0, 3.0}};
  Race r({k}, 90, settings, 0);
  std::int64_t runs_of_worst = 0;
  for (std::vector<RaceEvaluation> step = r.next(); !step.empty(); step = r.next()) {
    std::vector<double> costs;
    for (const RaceEvaluation& e : step) {
      const double v = r.candidate(e.config).values[0];
      std::uint64_t s = std::uint64_t(e.seed) + 11;
      // choice 2 always misses the target (+inf); 0 and 1 close, 0 better on most seeds.
      costs.push_back(v == 2 ? std::numeric_limits<double>::infinity() : 100 + 10 * v + 15 * uniform01(s));
      runs_of_worst += v == 2;
    }
    r.take(costs);
  }
  ASSERT_NE(r.best(), 0);
  EXPECT_EQ(r.candidate(r.best()).values[0], 0.0);
  EXPECT_EQ(runs_of_worst, 5);  // dropped at the first test, after first_test seeds
  EXPECT_LE(r.spent(), 90);
}

TEST(Race, WilcoxonEliminationFindsTheOptimumToo) {
  Race r = made_up_race(400, 2, RaceTest::wilcoxon);
  run_made_up(r);
  ASSERT_NE(r.best(), 0);
  EXPECT_EQ(r.candidate(r.best()).values[1], 0.0);
  EXPECT_NEAR(r.candidate(r.best()).values[0], 0.3, 0.1);
  EXPECT_LE(r.spent(), 400);
}

namespace {

struct Collected {
  std::vector<RunRow> rows;
  TuneOutcome outcome;
};

Collected tune_rows(const TuneSpec& t, const BatchEvaluator& ev, const std::vector<KnownRun>& known = {},
                    int shard_index = 0, int shard_count = 1) {
  Collected c;
  EnvironmentCache cache;
  TuneOptions opt;
  opt.shard_index = shard_index;
  opt.shard_count = shard_count;
  c.outcome = run_tune(
      t, ev, opt, [&](const std::vector<RunRow>& rows) { c.rows.insert(c.rows.end(), rows.begin(), rows.end()); },
      cache, known);
  return c;
}

KnownRun known_run(const RunRow& r) {
  return {r.tuple.run_id, param_hash(r.tuple.params, r.tuple.env_spec), tune_cost(r.result)};
}

}  // namespace

TEST(TuneRunner, RowsAreTheSameOnOneThreadOrTwoAndRunIdsCountEachCasesRuns) {
  const TuneSpec t = parse(two_parts + tune_ok);
  const Collected one = tune_rows(t, SerialBatchEvaluator());
  const Collected two = tune_rows(t, ThreadBatchEvaluator(2, best_simd_target()));
  ASSERT_EQ(one.rows.size(), two.rows.size());
  ASSERT_GT(one.rows.size(), 80u);
  std::map<std::string, std::int64_t> runs_of;  // per case label
  const std::map<std::string, std::int64_t> index{{"open", 0}, {"box", 1}, {"plain", 2}};
  for (std::size_t k = 0; k < one.rows.size(); ++k) {
    const RunRow &a = one.rows[k], &b = two.rows[k];
    // The case's k-th run: case + cases * k.
    EXPECT_EQ(a.tuple.run_id, index.at(a.tuple.label) + 3 * runs_of[a.tuple.label]++);
    EXPECT_EQ(a.tuple.run_id, b.tuple.run_id);
    EXPECT_EQ(param_hash(a.tuple.params, a.tuple.env_spec), param_hash(b.tuple.params, b.tuple.env_spec));
    EXPECT_EQ(a.tuple.race_round, b.tuple.race_round);
    EXPECT_EQ(a.tuple.config_id, b.tuple.config_id);
    EXPECT_EQ(a.result.steps, b.result.steps);
    EXPECT_EQ(std::isnan(a.result.coverage_time) ? -1.0 : a.result.coverage_time,
              std::isnan(b.result.coverage_time) ? -1.0 : b.result.coverage_time);
    if (a.tuple.race_round == 0) {
      EXPECT_GE(a.tuple.params.seed, t.validation_first_seed);
    } else {
      EXPECT_LT(a.tuple.params.seed, 1000);
      EXPECT_GE(a.tuple.race_round, 1);
    }
  }
  // Every case is validated on 4 seeds: the two raced ones with their choice, the plain one as given.
  std::map<std::string, int> validated;
  for (const RunRow& r : one.rows)
    if (r.tuple.race_round == 0) ++validated[r.tuple.label];
  EXPECT_EQ(validated, (std::map<std::string, int>{{"box", 4}, {"open", 4}, {"plain", 4}}));
  EXPECT_EQ(one.outcome.chosen[2], 1);
  EXPECT_LE(one.outcome.races[0]->spent(), 60);
}

TEST(TuneRunner, AReplayFromStoredRowsRunsOnlyWhatTheyLackAndRefusesOtherRows) {
  const TuneSpec t = parse(two_parts + tune_ok);
  const Collected full = tune_rows(t, SerialBatchEvaluator());
  // The first 37 rows stored (a kill mid-step): the replay runs the rest, the same.
  std::vector<KnownRun> known;
  for (std::size_t k = 0; k < 37; ++k) known.push_back(known_run(full.rows[k]));
  const Collected rest = tune_rows(t, SerialBatchEvaluator(), known);
  ASSERT_EQ(rest.rows.size(), full.rows.size() - 37);
  for (std::size_t k = 0; k < rest.rows.size(); ++k) {
    EXPECT_EQ(rest.rows[k].tuple.run_id, full.rows[k + 37].tuple.run_id);
    EXPECT_EQ(rest.rows[k].result.steps, full.rows[k + 37].result.steps);
  }
  known[20].param_hash ^= 1;
  try {
    tune_rows(t, SerialBatchEvaluator(), known);
    ADD_FAILURE() << "a stored row of other parameters was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(), "row 20 is stored as run_id " + std::to_string(known[20].run_id))) << e.what();
    EXPECT_TRUE(has(e.what(), "param_hash differs")) << e.what();
  }
  known[20] = known_run(full.rows[20]);
  known[21].run_id += 3;  // another shard's, or another case's run
  try {
    tune_rows(t, SerialBatchEvaluator(), known);
    ADD_FAILURE() << "a stored row of another run_id was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(), "row 21 is stored as run_id")) << e.what();
  }
}

// The cases race independently: shards 0/2 and 1/2 race cases {0, 2} and
// {1}, and their rows, run_ids and choices are the whole tune's.
TEST(TuneRunner, AShardOfTheCasesGivesTheWholeTunesRowsForThem) {
  const TuneSpec t = parse(two_parts + tune_ok);
  const Collected whole = tune_rows(t, SerialBatchEvaluator());
  std::map<std::int64_t, const RunRow*> by_id;
  for (const RunRow& r : whole.rows) by_id[r.tuple.run_id] = &r;
  std::size_t rows = 0;
  for (int k = 0; k < 2; ++k) {
    const Collected part = tune_rows(t, ThreadBatchEvaluator(2, best_simd_target()), {}, k, 2);
    EXPECT_EQ(part.outcome.cases, (k == 0 ? std::vector<std::size_t>{0, 2} : std::vector<std::size_t>{1}));
    for (std::size_t i : part.outcome.cases) EXPECT_EQ(part.outcome.chosen[i], whole.outcome.chosen[i]);
    for (const RunRow& r : part.rows) {
      ASSERT_TRUE(by_id.count(r.tuple.run_id)) << r.tuple.run_id;
      const RunRow& w = *by_id[r.tuple.run_id];
      EXPECT_EQ(int(r.tuple.run_id % 3) % 2, k);  // its case i = run_id % 3, and i % 2 == k
      EXPECT_EQ(r.tuple.label, w.tuple.label);
      EXPECT_EQ(param_hash(r.tuple.params, r.tuple.env_spec), param_hash(w.tuple.params, w.tuple.env_spec));
      EXPECT_EQ(r.tuple.race_round, w.tuple.race_round);
      EXPECT_EQ(r.tuple.config_id, w.tuple.config_id);
      EXPECT_EQ(r.result.steps, w.result.steps);
    }
    rows += part.rows.size();
  }
  EXPECT_EQ(rows, whole.rows.size());
}
