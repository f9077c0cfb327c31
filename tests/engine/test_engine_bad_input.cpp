// Bad input to the engine's readers (issue 11, docs/inputs.md): sweep specs,
// environment files and result files. Each test pins what the user gets: an
// error naming the file, the field (or line) and, for values, the allowed
// range.
#include <gtest/gtest.h>

#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/spec/environment_loader.hpp"
#include "engine/spec/run_tuple.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "engine/store/h5_store.hpp"
#include "kernels/planners/planner.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::has;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

// The error parse_sweep_spec gives for `text` (named spec.toml), or "" when it parses.
std::string spec_error(const std::string& text) {
  try {
    parse_sweep_spec(text, "spec.toml");
  } catch (const SpecError& e) {
    return e.what();
  }
  return "";
}

// The error loading `text` as an environment file gives (on a 10 m map), or "".
std::string env_error(const std::string& text) {
  try {
    parse_environment(text, "env.toml", 10, 10);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// ------------------------------------------------------------- sweep specs

TEST(SweepSpec, MalformedTomlIsRefusedNamingTheFileAndTheLine) {
  std::string e = spec_error("[sweep]\nname = \"x\"\n[fixed]\nsr = 1\nA = = 2\n");
  EXPECT_TRUE(has(e, "spec.toml: ")) << e;
  EXPECT_TRUE(has(e, "line 5")) << e;
  e = spec_error("[fixed]\nlabel = \"unterminated\n");
  EXPECT_TRUE(has(e, "spec.toml: ") && has(e, "line 2")) << e;
  e = spec_error("[fixed]\nsr = 1\n[fixed]\nsr = 2\n");  // a table defined twice
  EXPECT_TRUE(has(e, "spec.toml: ") && has(e, "line 3")) << e;
}

TEST(SweepSpec, UnknownKeysAndSectionsAreRefusedListingTheAllowedOnes) {
  std::string e = spec_error("[fixed]\nfoo = 1\n");
  EXPECT_TRUE(has(e, "spec.toml: fixed.foo: unknown key 'foo' (known: env, label, size, start, ic, planner")) << e;
  EXPECT_TRUE(has(e, "ds_index")) << e;
  e = spec_error("[fixd]\nA = 1\n");
  EXPECT_TRUE(has(e, "unknown section 'fixd' (allowed: [sweep], [fixed], [axes]")) << e;
  e = spec_error("[sweep]\nnmae = \"x\"\n");
  EXPECT_TRUE(has(e, "unknown key 'sweep.nmae' (allowed: name, description, extends)")) << e;
  e = spec_error("[axes]\nA = { start = 0, stop = 1, nun = 3 }\n");
  EXPECT_TRUE(has(e, "axes.A") && has(e, "'nun'")) << e;
}

TEST(SweepSpec, WrongTypesAreRefusedNamingTheKeyAndTheExpectedType) {
  std::string e = spec_error("[fixed]\nA = \"big\"\n");
  EXPECT_TRUE(has(e, "fixed.A: A must be a number, not \"big\"")) << e;
  e = spec_error("[fixed]\nplanner = 3\n");
  EXPECT_TRUE(has(e, "fixed.planner") && has(e, "must be one of arnold, logistic")) << e;
  e = spec_error("[fixed]\nds_index = 1.5\n");
  EXPECT_TRUE(has(e, "fixed.ds_index") && has(e, "must be an integer in [1, 3]")) << e;
  e = spec_error("[axes]\nA = 3\n");
  EXPECT_TRUE(has(e, "axes.A: must be a list of values or a range {start, stop, step|num}")) << e;
  e = spec_error("[fixed]\nstart = 3\n");
  EXPECT_TRUE(has(e, "fixed.start") && has(e, "2 numbers")) << e;
  e = spec_error("[fixed]\nenv = 5\n");
  EXPECT_TRUE(has(e, "fixed.env") && has(e, "environment name or a path")) << e;
}

TEST(SweepSpec, NanAndInfValuesAreOutOfRangeNamingTheKeyAndTheRange) {
  // TOML has nan and inf literals; no parameter accepts them.
  for (const char* v : {"nan", "inf", "-inf", "+nan"}) {
    const std::string e = spec_error(std::string("[fixed]\nA = ") + v + "\n");
    EXPECT_TRUE(has(e, "spec.toml: fixed.A: A = ")) << e;
    EXPECT_TRUE(has(e, "is out of range: must be a number in [-1000, 1000]")) << e;
  }
  std::string e = spec_error("[fixed]\nsr = inf\n");
  EXPECT_TRUE(has(e, "fixed.sr: sr = inf is out of range: must be a number in [0.001, 10000]")) << e;
  e = spec_error("[axes]\nA = [0.5, nan]\n");
  EXPECT_TRUE(has(e, "axes.A[1]: A = nan is out of range: must be a number in [-1000, 1000]")) << e;
  e = spec_error("[axes]\nA = { start = 0, stop = nan, num = 3 }\n");
  EXPECT_TRUE(has(e, "axes.A") && has(e, "[-1000, 1000]")) << e;
  e = spec_error("[axes]\nA = { start = 0, stop = inf, step = 0.1 }\n");
  EXPECT_TRUE(has(e, "axes.A")) << e;
  e = spec_error("[fixed]\nsize = inf\n");
  EXPECT_TRUE(has(e, "fixed.size: size_x = inf is out of range: must be a number in [0.001, 1e+06]")) << e;
  e = spec_error("[[zip]]\nA = [0.5, 0.6]\ndc = [0.9, nan]\n");
  EXPECT_TRUE(has(e, "zip[0].dc[1]") && has(e, "out of range")) << e;
  e = spec_error("case = [ { label = \"x\", f = -inf } ]\n");
  EXPECT_TRUE(has(e, "case[0].f") && has(e, "out of range")) << e;
}

TEST(SweepSpec, OutOfRangeValuesNameTheKeyAndTheRange) {
  std::string e = spec_error("[fixed]\ndc = 1.5\n");
  EXPECT_TRUE(has(e, "fixed.dc: dc = 1.5 is out of range: must be a number in [")) << e;
  e = spec_error("[axes]\nniter = [1000, 0]\n");
  EXPECT_TRUE(has(e, "axes.niter[1]: niter = 0 is out of range: must be an integer in [")) << e;
  e = spec_error("[sample]\nmethod = \"lhs\"\nn = 4\nA = { min = 0.4, max = 2000 }\n");
  EXPECT_TRUE(has(e, "sample.A") && has(e, "[-1000, 1000]")) << e;
}

TEST(SweepSpec, EmptyAxesAreRefusedNamingTheAxis) {
  EXPECT_TRUE(has(spec_error("[axes]\nA = []\n"), "spec.toml: axes.A: is empty: an axis needs at least one value"));
  EXPECT_TRUE(has(spec_error("[[zip]]\nA = []\nB = []\n"), "zip[0].A: is empty"));
  EXPECT_TRUE(has(spec_error("[[part]]\nname = \"p\"\n[part.axes]\nc = []\n"), "part[0].axes.c: is empty"));
  EXPECT_TRUE(has(spec_error("[axes]\nA = { start = 0.5, stop = 0.4, step = 0.1 }\n"), "axes.A"));
  EXPECT_TRUE(has(spec_error("[sample]\nmethod = \"lhs\"\nn = 0\nA = { min = 0, max = 1 }\n"),
                  "sample.n: must be in [1, 1e8]"));
  EXPECT_TRUE(has(spec_error("[repeat]\ncount = 0\n"), "repeat.count: must be in [1, 1e8]"));
}

TEST(SweepSpec, AnAxisOfAKeyThatDoesNotExistIsRefusedNamingTheKey) {
  std::string e = spec_error("[axes]\nfoo = [1, 2]\n");
  EXPECT_TRUE(has(e, "spec.toml: axes.foo[0]: unknown key 'foo' (known: env, label")) << e;
  e = spec_error("[[zip]]\nA = [0.4, 0.5]\nbar = [1, 2]\n");
  EXPECT_TRUE(has(e, "zip[0].bar") && has(e, "unknown key 'bar'")) << e;
  e = spec_error("[sample]\nmethod = \"random\"\nn = 3\nbaz = { min = 0, max = 1 }\n");
  EXPECT_TRUE(has(e, "sample") && has(e, "baz")) << e;
}

TEST(SweepSpec, ExtendingAMissingSpecIsRefusedNamingThatFile) {
  TempDir tmp;
  write_file(tmp.file("child.toml"), "[sweep]\nextends = \"no_such_parent.toml\"\n[axes]\nA = [0.4]\n");
  try {
    load_sweep_spec(tmp.file("child.toml"));
    FAIL() << "accepted";
  } catch (const SpecError& e) {
    EXPECT_TRUE(has(e.what(), "no_such_parent.toml")) << e.what();
    EXPECT_TRUE(has(e.what(), "sweep.extends")) << e.what();
  }
  try {
    load_sweep_spec(tmp.file("no_such_spec.toml"));
    FAIL() << "accepted";
  } catch (const SpecError& e) {
    EXPECT_TRUE(has(e.what(), "no_such_spec.toml")) << e.what();
  }
}

TEST(SweepSpec, AnEnvironmentThatDoesNotExistIsNamed) {
  // The spec parser takes env as text; the environment is loaded (and a
  // missing one refused) before the first run: see CliSweep.AnEnvironmentThatDoesNotExistIsNamedAndNothingIsWritten.
  try {
    load_environment("no_such_environment", 50, 50);
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(), "environment 'no_such_environment' not found")) << e.what();
  }
  try {
    load_environment("/nonexistent/dir/env.toml", 50, 50);
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(), "/nonexistent/dir/env.toml")) << e.what();
  }
}

// ------------------------------------------------------- environment files

TEST(Environment, MalformedFileIsRefusedNamingTheFileAndTheLine) {
  std::string e = env_error("name = \"x\"\nobstacles = [\n  { x = 0.1, y = 0.1, w = 0.1 h = 0.1 },\n]\n");
  EXPECT_TRUE(has(e, "environment env.toml: ")) << e;
  EXPECT_TRUE(has(e, "line 3")) << e;
  e = env_error("obstacles = [\n");
  EXPECT_TRUE(has(e, "environment env.toml: ") && has(e, "line")) << e;
  e = env_error("size = 10\nsize = 20\n");  // a key set twice
  EXPECT_TRUE(has(e, "line 2")) << e;
}

TEST(Environment, UnknownKeysAreRefusedListingTheAllowedOnes) {
  std::string e = env_error("colour = \"red\"\n");
  EXPECT_TRUE(has(e,
                  "environment env.toml: unknown key 'colour' (allowed: name, description, units, size, start, "
                  "start_units, obstacles, clutter)"))
      << e;
  e = env_error("obstacles = [{ x = 0.1, y = 0.1, w = 0.1, h = 0.1, d = 1 }]\n");
  EXPECT_TRUE(has(e, "obstacles[0] has unknown key 'd' (allowed: x, y, w, h)")) << e;
  e = env_error("clutter = { seed = 1, density = 0.1 }\n");
  EXPECT_TRUE(has(e, "unknown key 'clutter.density' (allowed: seed, occupancy, min_side, max_side, gap)")) << e;
}

TEST(Environment, WrongTypesAreRefusedNamingTheKey) {
  EXPECT_TRUE(has(env_error("size = \"big\"\n"), "'size' must be a number or [x, y]"));
  EXPECT_TRUE(has(env_error("size = [1, 2, 3]\n"), "'size' must be a number or [x, y]"));
  EXPECT_TRUE(has(env_error("name = 3\n"), "'name' must be a string"));
  EXPECT_TRUE(has(env_error("units = \"km\"\n"), "'units' must be \"relative\" (fractions of the map side) or \"m\""));
  EXPECT_TRUE(has(env_error("start = [0.5, 0.5]\nstart_units = 1\n"), "'start_units' must be \"relative\" or \"m\""));
  EXPECT_TRUE(has(env_error("obstacles = 3\n"), "'obstacles' must be an array of {x, y, w, h} tables"));
  EXPECT_TRUE(has(env_error("obstacles = [1]\n"), "obstacles[0] must be a table {x, y, w, h}"));
  EXPECT_TRUE(
      has(env_error("obstacles = [{ x = \"a\", y = 0.1, w = 0.1, h = 0.1 }]\n"), "'obstacles[0].x' must be a number"));
  EXPECT_TRUE(has(env_error("clutter = 3\n"), "'clutter' must be a table"));
}

TEST(Environment, NanAndInfAreRefusedNamingTheKey) {
  std::string e = env_error("size = inf\n");
  EXPECT_TRUE(has(e, "environment env.toml: 'size' = inf must be a finite number")) << e;
  EXPECT_TRUE(has(env_error("units = \"m\"\nsize = [10, nan]\n"), "'size[1]' = nan must be a finite number"));
  EXPECT_TRUE(has(env_error("obstacles = [{ x = nan, y = 0.1, w = 0.1, h = 0.1 }]\n"),
                  "'obstacles[0].x' = nan must be a finite number"));
  EXPECT_TRUE(has(env_error("obstacles = [{ x = 0.1, y = 0.1, w = inf, h = 0.1 }]\n"),
                  "'obstacles[0].w' = inf must be a finite number"));
  EXPECT_TRUE(has(env_error("start = [-inf, 0.5]\n"), "'start[0]' = -inf must be a finite number"));
  EXPECT_TRUE(has(env_error("size = 0\n"), "'size' = 0 x 0 must be positive"));
  EXPECT_TRUE(
      has(env_error("obstacles = [{ x = 0.1, y = 0.1, w = 0, h = 0.1 }]\n"), "obstacles[0]: w and h must be positive"));
}

TEST(Environment, AnObstacleOutsideTheMapIsRefusedNamingItAndTheMapBounds) {
  // Partly outside (relative units, on the run's 10 m map): the second obstacle.
  std::string e = env_error(
      "obstacles = [\n  { x = 0.1, y = 0.1, w = 0.1, h = 0.1 },\n  { x = 0.8, y = 0.1, w = 0.4, h = 0.1 },\n]\n");
  EXPECT_TRUE(has(e,
                  "environment env.toml: obstacles[1] spans [8, 12] x [1, 2] m: it reaches outside the map "
                  "[0, 10] x [0, 10] m"))
      << e;
  EXPECT_TRUE(has(e, "x + w <= 1")) << e;
  // Wholly outside.
  e = env_error("obstacles = [{ x = 1.5, y = 1.5, w = 0.4, h = 0.1 }]\n");
  EXPECT_TRUE(has(e, "obstacles[0] spans [15, 19] x [15, 16] m: it lies outside the map [0, 10] x [0, 10] m")) << e;
  // Metres: a negative corner, and past the file's own size.
  e = env_error("units = \"m\"\nsize = [20, 10]\nobstacles = [{ x = -1, y = 2, w = 3, h = 2 }]\n");
  EXPECT_TRUE(has(e, "obstacles[0] spans [-1, 2] x [2, 4] m: it reaches outside the map [0, 20] x [0, 10] m")) << e;
  EXPECT_FALSE(has(e, "relative")) << e;
  e = env_error("units = \"m\"\nsize = [20, 10]\nobstacles = [{ x = 15, y = 8, w = 2, h = 3 }]\n");
  EXPECT_TRUE(has(e, "obstacles[0] spans [15, 17] x [8, 11] m: it reaches outside the map [0, 20] x [0, 10] m")) << e;
  // Touching the edge is inside, whatever the rounding of x + w.
  EXPECT_EQ(env_error("obstacles = [{ x = 0.7, y = 0.6, w = 0.3, h = 0.4 }, { x = 0, y = 0, w = 0.1, h = 0.1 }]\n"),
            "");
  EXPECT_EQ(env_error("units = \"m\"\nsize = 10\nobstacles = [{ x = 9, y = 0, w = 1, h = 10 }]\n"), "");
}

TEST(Environment, ClutterThatCannotFitInTheMapIsRefusedAndGeneratedObstaclesStayInside) {
  // A side (plus its gaps) as large as the map: no obstacle could be placed.
  const std::string e = env_error("clutter = { seed = 1, occupancy = 0.1, min_side = 0.5, max_side = 0.99 }\n");
  EXPECT_TRUE(has(e, "clutter.max_side + 2 gap")) << e;
  EXPECT_TRUE(has(e, "= 10.3 m does not fit in the map (10 x 10 m)")) << e;
  // Sides up to most of the map: every generated obstacle lies inside it.
  for (std::uint64_t seed = 0; seed < 50; ++seed) {
    const Environment env = parse_environment("clutter = { seed = " + std::to_string(seed) +
                                                  ", occupancy = 0.3, min_side = 0.1, max_side = 0.9, gap = 0.02 }\n",
                                              "env.toml", 10, 10);
    for (const Rect& r : env.obstacles) {
      EXPECT_GE(r.x0, 0.0);
      EXPECT_GE(r.y0, 0.0);
      EXPECT_LE(r.x1, 10.0);
      EXPECT_LE(r.y1, 10.0);
    }
  }
}

TEST(Environment, OverlappingObstaclesAreAcceptedAsTheirUnion) {
  // Two overlapping squares, and the same region cut into three disjoint rectangles.
  const Environment overlap = parse_environment(
      "obstacles = [{ x = 0.2, y = 0.2, w = 0.4, h = 0.4 }, { x = 0.4, y = 0.4, w = 0.4, h = 0.4 }]\n", "o.toml", 10,
      10);
  const Environment disjoint = parse_environment(
      "obstacles = [{ x = 0.2, y = 0.2, w = 0.4, h = 0.4 }, { x = 0.6, y = 0.4, w = 0.2, h = 0.4 },\n"
      "             { x = 0.4, y = 0.6, w = 0.2, h = 0.2 }]\n",
      "d.toml", 10, 10);
  ASSERT_EQ(overlap.obstacles.size(), 2u);
  EXPECT_NEAR(overlap.obstacle_area(), 16 + 16 - 4, 1e-9);  // the overlap counted once
  EXPECT_NEAR(disjoint.obstacle_area(), overlap.obstacle_area(), 1e-9);
  // The run sees the union: the same free cells and the same T_opt.
  RunParams p = test::small_run(10);
  p.max_time = 50;
  const RunResult a = run_planner(p, overlap), b = run_planner(p, disjoint);
  EXPECT_EQ(a.free_cells, 100 - 28);
  EXPECT_EQ(a.free_cells, b.free_cells);
  EXPECT_DOUBLE_EQ(a.t_opt, b.t_opt);
  // A point in the overlap is inside an obstacle; a start there is refused.
  EXPECT_GE(overlap.obstacle_at(5, 5), 0);
  p.start_x = p.start_y = 5;
  EXPECT_EQ(run_planner(p, overlap).status, Status::invalid);
}

TEST(Environment, AStartInsideAnObstacleIsRefusedNamingTheObstacle) {
  // The file's own start: refused when the file is read.
  const std::string e = env_error(
      "start = [0.5, 0.5]\nobstacles = [{ x = 0, y = 0, w = 0.1, h = 0.1 }, { x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n");
  EXPECT_TRUE(has(e, "environment env.toml: 'start' = (5, 5) m lies inside obstacles[1]")) << e;
  // A run's own start (a flag or a spec axis): the run is invalid, naming the obstacle.
  const Environment env = test::square_map(10, {{4, 4, 6, 6}});
  RunParams p = test::small_run(10);
  p.start_x = p.start_y = 5;
  const RunResult r = run_planner(p, env);
  EXPECT_EQ(r.status, Status::invalid);
  EXPECT_TRUE(has(r.message, "start (5, 5) lies inside obstacle #0")) << r.message;
}

TEST(Environment, AStartOutsideTheMapIsRefusedNamingTheMapBounds) {
  std::string e = env_error("start = [1.5, 0.5]\n");
  EXPECT_TRUE(has(e, "environment env.toml: 'start' = (15, 5) m is outside the map [0, 10] x [0, 10] m")) << e;
  e = env_error("start = [-1, 1]\nstart_units = \"m\"\n");
  EXPECT_TRUE(has(e, "'start' = (-1, 1) m is outside the map")) << e;
  // On the edge is inside.
  EXPECT_EQ(env_error("start = [1, 0]\n"), "");
  const Environment env = test::square_map(10);
  RunParams p = test::small_run(10);
  p.start_x = 12;
  const RunResult r = run_planner(p, env);
  EXPECT_EQ(r.status, Status::invalid);
  EXPECT_TRUE(has(r.message, "start (12, 0.5) is outside the map [0, 10] x [0, 10]")) << r.message;
}

// ------------------------------------------------------------ result files

namespace {

// A real result file of `n` hand-made rows, written by the store's writer.
void write_result_file(const std::string& path, int n) {
  std::vector<RunRow> rows(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    rows[std::size_t(i)].tuple.run_id = i;
    rows[std::size_t(i)].tuple.params = test::small_run(10);
    rows[std::size_t(i)].result.status = Status::ok;
    rows[std::size_t(i)].result.coverage_time = 100 + i;
  }
  H5RunWriter w(path);
  w.set_attribute("spec_hash", "0123");
  w.append(rows);
  w.finish();
}

void truncate_to_half(const std::string& from, const std::string& to) {
  const std::string bytes = test::read_file(from);
  write_file(to, bytes.substr(0, bytes.size() / 2));
}

}  // namespace

TEST(H5Store, BrokenAndForeignFilesAreNamedWithoutAnHdf5ErrorDump) {
  TempDir tmp;
  write_result_file(tmp.file("good.h5"), 3000);
  ASSERT_EQ(count_rows(tmp.file("good.h5")), 3000);
  truncate_to_half(tmp.file("good.h5"), tmp.file("truncated.h5"));
  write_file(tmp.file("text.h5"), "run_id,status\n0,ok\n");
  chaosweep::test::write_foreign_file(tmp.file("no-runs.h5"), "no-runs");
  chaosweep::test::write_foreign_file(tmp.file("not-compound.h5"), "not-compound");
  struct Case {
    const char* file;
    const char* why;
  };
  for (const Case& c :
       {Case{"truncated.h5", "is truncated or damaged: HDF5 cannot open it"}, Case{"text.h5", "is not an HDF5 file"},
        Case{"missing.h5", "does not exist"}, Case{"no-runs.h5", "has no /runs dataset"},
        Case{"not-compound.h5", "/runs is not a table of columns"}}) {
    const std::string path = tmp.file(c.file);
    auto expect_named = [&](const char* reader, auto&& read) {
      testing::internal::CaptureStderr();
      std::string what;
      try {
        read();
      } catch (const std::runtime_error& e) {
        what = e.what();
      }
      const std::string err = testing::internal::GetCapturedStderr();
      EXPECT_TRUE(has(what, path)) << reader << " " << c.file << ": " << what;
      EXPECT_TRUE(has(what, c.why)) << reader << " " << c.file << ": " << what;
      EXPECT_EQ(err, "") << reader << " " << c.file << " printed HDF5's error stack";
    };
    expect_named("count_rows", [&] { count_rows(path); });
    expect_named("read_all_columns", [&] { read_all_columns(path); });
    expect_named("column_names", [&] { column_names(path); });
    expect_named("read_f64_column", [&] { read_f64_column(path, "coverage_time"); });
  }
  // A result file lacking an attribute, or a column: named, quietly.
  testing::internal::CaptureStderr();
  EXPECT_THROW(read_attribute(tmp.file("good.h5"), "no_such_attribute"), std::runtime_error);
  EXPECT_THROW(read_f64_column(tmp.file("good.h5"), "no_such_column"), std::runtime_error);
  EXPECT_THROW(read_attribute(tmp.file("no-runs.h5"), "spec_hash"), std::runtime_error);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  try {
    read_f64_column(tmp.file("good.h5"), "no_such_column");
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(), "no column 'no_such_column'")) << e.what();
  }
}
