// `chaosweep plan`'s work bound (issue 18, item 9): computed from the axes
// that set time budgets only, it equals the sum over every run, and a spec
// of 1e9 runs costs a handful of budgets, not 1e9.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/run/sweep_runner.hpp"
#include "engine/spec/work_bound.hpp"
#include "kernels/core/param_table.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

// The bound as `plan` computed it before: every run visited.
double every_run(const SweepSpec& spec, EnvironmentCache& cache) {
  double steps = 0;
  for (std::int64_t i = 0; i < spec.size(); ++i) {
    const RunTuple t = resolve_run(i, spec.run(i), cache);
    steps += run_step_bound(t.params, t.env->lx * t.env->ly - t.env->obstacle_area());
  }
  return steps;
}

void expect_same_bound(const std::string& text, const std::string& dir, std::int64_t evaluated) {
  const SweepSpec spec = parse_sweep_spec(text, "spec.toml", dir);
  EnvironmentCache cache;
  const WorkBound w = bound_work(spec, cache);
  EXPECT_FALSE(w.sampled) << text;
  EXPECT_NEAR(w.steps, every_run(spec, cache), 1e-12 * w.steps) << text;
  EXPECT_EQ(w.evaluated, evaluated) << text;
}

}  // namespace

TEST(WorkBound, EqualsTheSumOverEveryRunWhateverKeyTheAxesSet) {
  // An axis of each key (two values), beside a label axis of three that
  // sets no budget: the bound walks only what changes a budget.
  TempDir tmp;
  write_file(tmp.file("box.toml"), "units = \"m\"\nsize = 20\nobstacles = [{ x = 2, y = 2, w = 6, h = 6 }]\n");
  const std::string base = "[fixed]\nsize = 10\nsr = 2\n[axes]\nlabel = [\"a\", \"b\", \"c\"]\n";
  for (const ParamInfo& p : param_table()) {
    const std::string key(p.name);
    const std::string values =
        p.kind == ParamInfo::Kind::choice
            ? "[\"" + std::string(p.choices.front()) + "\", \"" + std::string(p.choices.back()) + "\"]"
            : "[" + format_number(p.lo) + ", " +
                  format_number(p.kind == ParamInfo::Kind::integer ? std::floor((p.lo + p.hi) / 2) : p.hi) + "]";
    std::string text = base + key + " = " + values + "\n";
    if (key == "sr" || key == "size_x" || key == "size_y") text = "[fixed]\n[axes]\n" + key + " = " + values + "\n";
    const bool budget = key == "max_time" || key == "max_pr" || key == "dc" || key == "sr" || key == "v" ||
                        key == "planner" || key == "dt_c" || key == "f" || key == "dt" || key == "size_x" ||
                        key == "size_y";
    SCOPED_TRACE(key);
    expect_same_bound(text, tmp.path().string(), budget ? 2 : 1);
  }
  expect_same_bound("[fixed]\nsr = 2\n[axes]\nlabel = [\"a\", \"b\", \"c\"]\nsize = [8, 12]\n", tmp.path().string(), 2);
  expect_same_bound(base + "env = [\"empty\", \"" + tmp.file("box.toml") + "\"]\n", tmp.path().string(), 2);
  expect_same_bound(base + "planner = [\"arnold\", \"logistic\"]\n", ".", 2);  // its step is dt_c, not f dt
  // max_time set: the budget is max_time; unset, it is max_pr x T_opt.
  expect_same_bound("[fixed]\nsize = 10\n[axes]\nmax_time = [0, 50]\nsr = [1, 2]\nA = [0.4, 0.5]\n", ".", 4);
}

TEST(WorkBound, PartsZipsCasesAndSamplesAreBoundedAsTheirRunsAre) {
  expect_same_bound(
      "[fixed]\nsize = 10\n[axes]\nA = [0.4, 0.5]\n"
      "[[part]]\nname = \"one\"\n[part.axes]\nsr = [1, 2, 4]\nB = [0.1, 0.2]\n"
      "[[part]]\nname = \"two\"\n[part.fixed]\nplanner = \"logistic\"\n[[part.zip]]\nsr = [1, 3]\nC = [0.2, 0.3]\n",
      ".", 3 + 2);
  expect_same_bound(
      "[fixed]\nsize = 10\n[[case]]\nlabel = \"x\"\nsr = 1\n[[case]]\nlabel = \"y\"\nsr = 3\n[axes]\nB = [0.1, 0.2]\n"
      "[repeat]\ncount = 5\nseed = 1\n",
      ".", 2);
  expect_same_bound("[fixed]\nsize = 10\n[sample]\nn = 50\nsr = { min = 1, max = 3 }\nA = { min = 0.3, max = 0.6 }\n",
                    ".", 50);
}

TEST(WorkBound, ASpecOfABillionRunsCostsOnlyItsBudgetAxes) {
  const std::string grid =
      "A = { start = 0.1, stop = 0.9, num = 1000 }\nB = { start = 0.1, stop = 0.9, num = 1000 }\n"
      "C = { start = 0.1, stop = 0.9, num = 1000 }\n";
  SweepSpec spec = parse_sweep_spec("[fixed]\nsize = 10\nsr = 2\n[axes]\n" + grid, "spec.toml");
  ASSERT_EQ(spec.size(), 1000000000);
  EnvironmentCache cache;
  WorkBound w = bound_work(spec, cache);
  EXPECT_EQ(w.evaluated, 1);
  EXPECT_FALSE(w.sampled);
  RunTuple t = resolve_run(0, spec.run(0), cache);
  EXPECT_DOUBLE_EQ(w.steps, 1e9 * run_step_bound(t.params, 100));
  spec = parse_sweep_spec("[fixed]\nsize = 10\n[axes]\nsr = [1, 2, 4]\n" + grid, "spec.toml");
  w = bound_work(spec, cache);
  EXPECT_EQ(w.evaluated, 3);
  // Budget axes with more combinations than max_exact: a seeded sample of
  // that many, close to the sum over every run.
  spec = parse_sweep_spec(
      "[fixed]\nsize = 10\n[sample]\nn = 20000\nsr = { min = 1, max = 3 }\n[axes]\nA = [0.4, 0.5]\n", "spec.toml");
  w = bound_work(spec, cache, 1000);
  EXPECT_TRUE(w.sampled);
  EXPECT_EQ(w.evaluated, 1000);
  EXPECT_NEAR(w.steps, every_run(spec, cache), 0.05 * w.steps);
  EXPECT_EQ(bound_work(spec, cache, 1000).steps, w.steps);  // the same draws each time
}
