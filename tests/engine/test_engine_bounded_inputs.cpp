// Inputs are bounded (issue 18, docs/inputs.md): the files a spec reads are
// regular files of bounded size, an `extends` chain cannot loop, integers
// the parser cannot hold exactly are named, and a spec that sets nothing is
// refused. Each test pins the message the user gets.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "engine/spec/environment_loader.hpp"
#include "engine/spec/input_file.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::has;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

// The error loading the spec at `path` gives, or "" when it loads.
std::string load_error(const std::string& path) {
  try {
    load_sweep_spec(path);
  } catch (const SpecError& e) {
    return e.what();
  }
  return "";
}

std::string env_load_error(const std::string& env) {
  try {
    load_environment(env, 10, 10);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SweepSpec, AnExtendsCycleIsRefusedNamingTheChain) {
  TempDir tmp;
  write_file(tmp.file("self.toml"), "[sweep]\nextends = \"self.toml\"\n[fixed]\nsr = 2\n");
  std::string e = load_error(tmp.file("self.toml"));
  EXPECT_TRUE(has(e, "self.toml: sweep.extends: \"self.toml\" is this spec itself: a spec cannot extend itself")) << e;
  write_file(tmp.file("a.toml"), "[sweep]\nextends = \"b.toml\"\n");
  write_file(tmp.file("b.toml"), "[sweep]\nextends = \"a.toml\"\n");
  e = load_error(tmp.file("a.toml"));
  EXPECT_TRUE(has(e, tmp.file("b.toml") + ": sweep.extends: \"a.toml\" makes a cycle of extended specs: " +
                         tmp.file("a.toml") + " -> " + tmp.file("b.toml") + " -> " + tmp.file("a.toml")))
      << e;
  // Through another spelling of the same file, and starting from text.
  write_file(tmp.file("c.toml"), "[sweep]\nextends = \"../" + tmp.path().filename().string() + "/c.toml\"\n");
  EXPECT_TRUE(has(load_error(tmp.file("c.toml")), "is this spec itself")) << load_error(tmp.file("c.toml"));
  try {
    parse_sweep_spec("[sweep]\nextends = \"a.toml\"\n", "text.toml", tmp.path().string());
    FAIL() << "accepted";
  } catch (const SpecError& x) {
    EXPECT_TRUE(has(x.what(), "makes a cycle of extended specs")) << x.what();
  }
  // A chain without a cycle (a diamond: two specs extend one) is fine, and
  // every file read is listed with its content hash.
  write_file(tmp.file("base.toml"), "[fixed]\nsr = 2\n");
  write_file(tmp.file("mid.toml"), "[sweep]\nextends = \"base.toml\"\n[axes]\nA = [0.4, 0.5]\n");
  write_file(tmp.file("top.toml"), "[sweep]\nextends = \"mid.toml\"\n[axes]\nB = [0.1]\n");
  const SweepSpec s = load_sweep_spec(tmp.file("top.toml"));
  EXPECT_EQ(s.size(), 2);
  ASSERT_EQ(s.files.size(), 3u);
  EXPECT_EQ(s.files[0].path, tmp.file("top.toml"));
  EXPECT_EQ(s.files[1].path, tmp.file("mid.toml"));
  EXPECT_EQ(s.files[2].path, tmp.file("base.toml"));
  EXPECT_NE(s.files[1].hash, s.files[2].hash);
}

TEST(SweepSpec, OnlyRegularFilesOfBoundedSizeAreReadAsSpecsOrEnvironments) {
  TempDir tmp;
  ASSERT_EQ(mkfifo(tmp.file("fifo").c_str(), 0600), 0);
  std::filesystem::create_directory(tmp.file("dir"));
  // Each would block (a FIFO), never end (/dev/zero) or read as empty (a directory, /dev/null).
  struct Case {
    std::string path, kind;
  };
  for (const Case& c : {Case{tmp.file("fifo"), "is a FIFO (named pipe), not a regular file"},
                        Case{"/dev/zero", "is a character device, not a regular file"},
                        Case{"/dev/null", "is a character device, not a regular file"},
                        Case{tmp.file("dir"), "is a directory, not a regular file"},
                        Case{tmp.file("dir") + "/", "is a directory, not a regular file"}}) {
    std::string e = load_error(c.path);
    EXPECT_TRUE(has(e, c.path + ": the sweep spec " + c.kind)) << e;
    write_file(tmp.file("child.toml"), "[sweep]\nextends = \"" + c.path + "\"\n");
    e = load_error(tmp.file("child.toml"));
    EXPECT_TRUE(has(e, c.path + ": the spec named by sweep.extends " + c.kind)) << e;
    e = env_load_error(c.path);
    EXPECT_TRUE(has(e, "environment " + c.path + ": the environment file " + c.kind)) << e;
  }
  // A file over the cap: refused, saying the cap (a sparse file: no disk used).
  const std::string huge = tmp.file("huge.toml");
  write_file(huge, "# padding\n");
  std::filesystem::resize_file(huge, max_input_bytes + 1);
  EXPECT_TRUE(has(load_error(huge), huge + ": the sweep spec is larger than 16 MiB (the limit for an input file)"))
      << load_error(huge);
  EXPECT_TRUE(has(env_load_error(huge), "environment " + huge + ": the environment file is larger than 16 MiB"))
      << env_load_error(huge);
  // At the cap it is read (and parsed: a comment).
  std::filesystem::resize_file(huge, max_input_bytes);
  EXPECT_EQ(read_input_file(huge, "x").size(), max_input_bytes);
  // A missing file says why.
  EXPECT_TRUE(
      has(load_error(tmp.file("none.toml")), "none.toml: cannot open the sweep spec (No such file or directory)"));
}

TEST(SweepSpec, IntegersBeyondTwoToThe53AreRefusedNamingTheKey) {
  // toml++ cannot give these as doubles; reading them as numbers read garbage.
  struct Case {
    const char* spec;
    const char* message;
  };
  for (const Case& c :
       {Case{"[axes]\nA = { start = 0.1, stop = 0.2, num = 9223372036854775807 }\n",
             "spec.toml: axes.A.num = 9223372036854775807 is too large: integers must lie within +-2^53"},
        Case{"[fixed]\nseed = -9007199254740993\n", "spec.toml: fixed.seed = -9007199254740993 is too large"},
        Case{"[axes]\nsr = [1, 9007199254740993]\n", "spec.toml: axes.sr[1] = 9007199254740993 is too large"},
        Case{"[[zip]]\nsr = [1, 2]\nA = [0.4, 9223372036854775807]\n", "spec.toml: zip[0].A[1] = 9223372036854775807"},
        Case{"[repeat]\ncount = 2\nseed = 9223372036854775807\n", "spec.toml: repeat.seed = 9223372036854775807"}}) {
    std::string e;
    try {
      parse_sweep_spec(c.spec, "spec.toml");
    } catch (const SpecError& x) {
      e = x.what();
    }
    EXPECT_TRUE(has(e, c.message)) << c.spec << ": " << e;
  }
  // 2^53 itself is exact: an ordinary out-of-range value.
  try {
    parse_sweep_spec("[axes]\nA = { start = 0.1, stop = 0.2, num = 9007199254740992 }\n", "spec.toml");
    FAIL() << "accepted";
  } catch (const SpecError& x) {
    EXPECT_TRUE(has(x.what(), "axes.A.num: must be a whole number in [1, 1e8], not 9")) << x.what();
  }
  // Environment files alike.
  try {
    parse_environment("clutter = { seed = 9223372036854775807 }\n", "env.toml", 10, 10);
    FAIL() << "accepted";
  } catch (const std::runtime_error& x) {
    EXPECT_TRUE(has(x.what(), "environment env.toml: clutter.seed = 9223372036854775807 is too large")) << x.what();
  }
  // A float seed beyond 2^53 (found by the fuzzer: its conversion was undefined behaviour).
  try {
    parse_environment("clutter = { seed = 8888888888888888888888888888.03 }\n", "env.toml", 10, 10);
    FAIL() << "accepted";
  } catch (const std::runtime_error& x) {
    EXPECT_TRUE(has(x.what(), "environment env.toml: clutter.seed = 8.88889e+27 must be a whole number in [0, 2^53]"))
        << x.what();
  }
}

TEST(SweepSpec, AValueOfTheWrongTypeIsNamedOnce) {
  try {
    parse_sweep_spec("[fixed]\nds_index = true\n", "spec.toml");
    FAIL() << "accepted";
  } catch (const SpecError& e) {
    EXPECT_EQ(std::string(e.what()), "spec.toml: fixed.ds_index: must be a number, a string or an array of numbers");
  }
}

TEST(SweepSpec, ASpecThatSetsNothingIsRefused) {
  for (const char* text : {"", "# only a comment\n\n", "[sweep]\n[fixed]\n[axes]\n"}) {
    try {
      parse_sweep_spec(text, "spec.toml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const SpecError& e) {
      EXPECT_TRUE(has(e.what(),
                      "spec.toml: the spec is empty (it sets nothing): it would be one run of the default parameters"))
          << e.what();
    }
  }
  // An extended spec that sets nothing is named; one that sets something carries its child.
  TempDir tmp;
  write_file(tmp.file("empty.toml"), "");
  write_file(tmp.file("child.toml"), "[sweep]\nextends = \"empty.toml\"\n");
  EXPECT_TRUE(has(load_error(tmp.file("child.toml")), "empty.toml: the spec is empty"))
      << load_error(tmp.file("child.toml"));
  write_file(tmp.file("base.toml"), "[fixed]\nsr = 2\n");
  write_file(tmp.file("child.toml"), "[sweep]\nextends = \"base.toml\"\n");
  EXPECT_EQ(load_error(tmp.file("child.toml")), "");
  // A spec that only names itself is one run of the defaults, as asked.
  EXPECT_EQ(parse_sweep_spec("[sweep]\nname = \"defaults\"\n", "spec.toml").size(), 1);
}

TEST(Environment, ClutterOfSquaresTooSmallForItsOccupancyIsRefused) {
  // 1e-9 of a 10 m map: 5e17 squares to reach 50%. The generator tried
  // 100,000 of them, each against every square placed: it seemed to hang.
  try {
    parse_environment("clutter = { seed = 1, occupancy = 0.5, min_side = 1e-9, max_side = 2e-9, gap = 0 }\n",
                      "env.toml", 10, 10);
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(),
                    "environment env.toml: clutter.occupancy = 0.5 with squares of min_side = 1e-08 m takes up "
                    "to 5e+17 squares (more than 100000, the generator's attempts): raise clutter.min_side or "
                    "lower clutter.occupancy"))
        << e.what();
  }
  // Many small squares within the bound: generated, and indexed for the run.
  const Environment env = parse_environment(
      "clutter = { seed = 1, occupancy = 0.1, min_side = 0.005, max_side = 0.006, gap = 0.001 }\n", "env.toml", 10, 10);
  EXPECT_GT(env.obstacles.size(), 1000u);
  EXPECT_NE(env.usable_index(), nullptr);
}
