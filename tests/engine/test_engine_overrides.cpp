// --set KEY=VALUE (engine/spec/spec_overrides): a change of the spec's own
// text, so that the stored spec re-parses to the runs that ran.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/spec/spec_overrides.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "tests/support/test_util.hpp"

namespace {

using namespace chaosweep;

const std::string spec_text =
    "# a comment\n[fixed]\nsize = 12  # m\nsr = 2\n[axes]\nA = [0.4, 0.5, 0.6]\nB = { start = 0.1, stop = 0.3, step = "
    "0.1 }\nds_index = [1, 2, 3]\n";

std::vector<SpecOverride> sets(const std::vector<std::string>& args) {
  std::vector<SpecOverride> out;
  for (const auto& a : args) out.push_back(parse_override(a));
  return out;
}

// Loads `text` from a file with the flags, as plan, sweep and slurm do.
SweepSpec with(const std::vector<std::string>& args, const std::string& text = spec_text) {
  chaosweep::test::TempDir tmp;
  chaosweep::test::write_file(tmp.file("s.toml"), text);
  return load_sweep_spec(tmp.file("s.toml"), sets(args));
}

std::string override_error_of(const std::vector<std::string>& args, const std::string& text = spec_text) {
  try {
    with(args, text);
  } catch (const SpecError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SpecOverrides, AFixedSettingAndAnAxisChangeWhereTheyAreWritten) {
  const SweepSpec s = with({"sr=4", "A=[0.45, 0.55]", "B={ start = 0.2, stop = 0.3, step = 0.1 }"});
  EXPECT_EQ(s.size(), 2 * 2 * 3);
  EXPECT_EQ(s.run(0).params.sr, 4.0);
  EXPECT_EQ(s.run(0).params.A, 0.45);
  EXPECT_EQ(s.run(11).params.A, 0.55);
  EXPECT_EQ(s.run(0).params.B, 0.2);
  EXPECT_EQ(s.run(3).params.B, 0.3);  // the exact decimal, as written on the command line
  // The axes keep their order (A slowest): run 1 differs from run 0 in ds_index only.
  EXPECT_EQ(s.run(1).params.A, 0.45);
  EXPECT_EQ(s.run(1).params.ds_index, 2);
}

TEST(SpecOverrides, AScalarForAnAxisIsOneValueAndAListForAFixedSettingSweepsItLast) {
  const SweepSpec one = with({"A=0.5"});
  EXPECT_EQ(one.size(), 3 * 3);
  EXPECT_EQ(one.run(0).params.A, 0.5);
  const SweepSpec more = with({"sr=[1, 4]"});
  EXPECT_EQ(more.size(), 3 * 3 * 3 * 2);
  EXPECT_EQ(more.run(0).params.sr, 1.0);
  EXPECT_EQ(more.run(1).params.sr, 4.0);  // written last in [axes]: varies fastest
  const SweepSpec fixed_start = with({"start=[0.25, 0.75]"});
  EXPECT_EQ(fixed_start.size(), 27);  // a tuple stays a fixed value
  EXPECT_EQ(fixed_start.run(0).params.start_y, 0.75);
  const SweepSpec new_key = with({"max_time=500", "env=five_squares"});
  EXPECT_EQ(new_key.run(0).params.max_time, 500.0);
  EXPECT_EQ(new_key.run(0).env, "five_squares");  // a bare word is text
  const std::string no_sections = "[axes]\nA = [0.4, 0.5]\n";
  EXPECT_EQ(with({"sr=3", "sweep.name=renamed"}, no_sections).run(0).params.sr, 3.0);
  EXPECT_EQ(with({"sweep.name=renamed"}, no_sections).name, "renamed");
}

TEST(SpecOverrides, TheStoredTextIsTheChangedSpecAndNamesTheFlags) {
  const std::string changed = apply_overrides(spec_text, sets({"sr=4"}), "s.toml");
  EXPECT_NE(changed.find("sr = 4\n"), std::string::npos) << changed;
  EXPECT_NE(changed.find("size = 12  # m\n"), std::string::npos) << "the rest of the text stays as written";
  EXPECT_NE(changed.find("# chaosweep --set sr=4\n"), std::string::npos) << changed;
  EXPECT_EQ(changed.find("# a comment\n"), 0u) << "line numbers of messages stay the file's";
  // Re-parsing the stored text gives the same runs without the flags.
  const SweepSpec again = parse_sweep_spec(changed, "stored");
  EXPECT_EQ(again.run(5).params.sr, 4.0);
  EXPECT_EQ(apply_overrides(spec_text, {}, "s.toml"), spec_text);
}

TEST(SpecOverrides, BadKeysAndValuesGetTheSpecsOwnErrorsNamingTheFlag) {
  EXPECT_NE(override_error_of({"sr=-1"}).find("must be a number in [0.001, 10000] (the spec with --set sr=-1)"),
            std::string::npos)
      << override_error_of({"sr=-1"});
  EXPECT_NE(override_error_of({"nope=3"}).find("unknown key 'nope'"), std::string::npos);
  EXPECT_NE(override_error_of({"A=[0.4,"}).find("--set A=[0.4,: the value is not a TOML value"), std::string::npos);
  EXPECT_NE(override_error_of({"sr=1", "fixed.sr=2"}).find("'sr' is given twice"), std::string::npos);
  EXPECT_NE(override_error_of({"sweep.extends=other.toml"}).find("only name and description"), std::string::npos);
  EXPECT_NE(override_error_of({"a.b.c=1"}).find("the key must be KEY, fixed.KEY, axes.KEY"), std::string::npos);
  const std::string zipped = "[fixed]\nsr = 2\n[[zip]]\nA = [0.4, 0.5]\nB = [0.1, 0.2]\n";
  EXPECT_NE(override_error_of({"A=0.3"}, zipped).find("'A' is set by the spec's [[zip]]"), std::string::npos)
      << override_error_of({"A=0.3"}, zipped);
  for (const std::string bad : {"A", "=3", "A="}) {
    try {
      parse_override(bad);
      ADD_FAILURE() << bad;
    } catch (const SpecError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--set ", 0), 0u) << e.what();
    }
  }
}

TEST(SpecOverrides, TheSpecHashFollowsTheFlagsOfALoadedSpec) {
  chaosweep::test::TempDir tmp;
  chaosweep::test::write_file(tmp.file("s.toml"), spec_text);
  const SweepSpec plain = load_sweep_spec(tmp.file("s.toml"));
  const SweepSpec set = load_sweep_spec(tmp.file("s.toml"), sets({"sr=4"}));
  EXPECT_NE(plain.text, set.text);
  EXPECT_EQ(set.run(0).params.sr, 4.0);
  EXPECT_EQ(plain.files.front().hash, set.files.front().hash) << "the file itself did not change";
}
