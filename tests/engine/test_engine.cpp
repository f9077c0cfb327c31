// Engine: environments, sweep specs, the TBB runner, the HDF5 store, JSON.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <thread>
#include <tuple>

#include "engine/rows/json_writer.hpp"
#include "engine/rows/result_columns.hpp"
#include "engine/run/all_pairs_plans.hpp"
#include "engine/run/progress.hpp"
#include "engine/run/serial_batch_evaluator.hpp"
#include "engine/run/simd_choice.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/run/sweep_summary.hpp"
#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/spec/environment_loader.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "engine/store/h5_compare.hpp"
#include "engine/store/h5_store.hpp"
#include "tests/support/sweep_rows.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::TempDir;
using chaosweep::test::write_file;

namespace {

// A ~few-second sweep: 3 x 3 x 2 x 2 runs of the original planner, small map.
const char* small_spec = R"(
[sweep]
name = "small"
[fixed]
size = 12
sr = 1
max_time = 3000
[axes]
C = [0.2, 0.25, 0.3]
A = { start = 0.4, stop = 0.6, num = 3 }
ds_index = [1, 3]
boundary = ["mirror", "fold"]
)";

std::string error_of(const std::string& text) {
  try {
    parse_sweep_spec(text, "spec.toml");
  } catch (const SpecError& e) {
    return e.what();
  }
  return "";
}

bool same_rows(const std::vector<RunRow>& a, const std::vector<RunRow>& b, std::string& diff) {
  if (a.size() != b.size()) {
    diff = "row counts differ";
    return false;
  }
  for (std::size_t i = 0; i < a.size(); ++i)
    for (const Column& c : result_columns()) {
      if (!c.deterministic) continue;
      const CellValue x = c.get(a[i]), y = c.get(b[i]);
      const bool both_nan = std::holds_alternative<double>(x) && std::holds_alternative<double>(y) &&
                            std::isnan(std::get<double>(x)) && std::isnan(std::get<double>(y));
      if (!both_nan && x != y) {
        diff = "row " + std::to_string(i) + " column " + c.name;
        return false;
      }
    }
  return true;
}

}  // namespace

// ------------------------------------------------------------- sweep specs

TEST(SweepSpec, ExpandsTheCartesianProductInFileOrder) {
  const SweepSpec s = parse_sweep_spec(small_spec, "spec.toml");
  ASSERT_EQ(s.axes.size(), 4u);
  EXPECT_EQ(s.axes[0].name(), "C");  // file order, not alphabetical
  EXPECT_EQ(s.axes[1].name(), "A");
  EXPECT_EQ(s.size(), 3 * 3 * 2 * 2);
  RunParams p = s.run(0).params;
  EXPECT_EQ(p.C, 0.2);
  EXPECT_EQ(p.A, 0.4);
  EXPECT_EQ(p.ds_index, 1);
  EXPECT_EQ(p.boundary, Boundary::mirror);
  EXPECT_EQ(p.size_x, 12.0);
  p = s.run(1).params;  // last axis varies fastest
  EXPECT_EQ(p.boundary, Boundary::fold);
  p = s.run(35).params;
  EXPECT_EQ(p.C, 0.3);
  EXPECT_EQ(p.A, 0.6);
  EXPECT_EQ(p.ds_index, 3);
}

TEST(SweepSpec, RangesIncludeTheirStopValue) {
  const SweepSpec s = parse_sweep_spec("[axes]\nB = { start = 0.1, stop = 0.8, step = 0.1 }\n", "x");
  ASSERT_EQ(s.axes[0].values.size(), 8u);
  EXPECT_NEAR(std::get<double>(s.axes[0].values.back()[0].second), 0.8, 1e-12);
  const SweepSpec t = parse_sweep_spec("[axes]\nB = { start = 0.1, stop = 0.8, num = 15 }\n", "x");
  EXPECT_EQ(std::get<double>(t.axes[0].values.back()[0].second), 0.8);
}

TEST(SweepSpec, ZipGroupsAdvanceTogetherAsOneAxis) {
  const SweepSpec s = parse_sweep_spec(
      "[axes]\nf = [1, 2]\n[[zip]]\nlabel = [\"r1\", \"r2\", \"r3\"]\nsize = [50, 100, 200]\n"
      "sr = [1, 1, 4]\n",
      "x");
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[1].name(), "zip(label, size, sr)");
  EXPECT_EQ(s.size(), 6);
  const RunSpec r = s.run(5);  // f = 2, third row
  EXPECT_EQ(r.params.f, 2.0);
  EXPECT_EQ(r.label, "r3");
  EXPECT_EQ(r.params.size_x, 200.0);
  EXPECT_EQ(r.params.sr, 4.0);
}

TEST(SweepSpec, CaseTablesAreOneAxisOfRows) {
  const SweepSpec s = parse_sweep_spec(
      "[fixed]\nsr = 2\n[axes]\nseed = [0, 1]\n"
      "[[case]]\nlabel = \"a\"\nsize = 20\n"
      "[[case]]\nlabel = \"b\"\nsize = 30\nmap_zoning = 1\nc = 0.5\n",
      "x");
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[1].kind, "case");
  EXPECT_EQ(s.size(), 4);
  EXPECT_EQ(s.run(0).label, "a");
  EXPECT_EQ(s.run(0).params.map_zoning, 0);  // a case sets only its own keys
  EXPECT_EQ(s.run(3).label, "b");
  EXPECT_EQ(s.run(3).params.c, 0.5);
  EXPECT_EQ(s.run(3).params.seed, 1);
  EXPECT_NE(error_of("[[case]]\nsize = 20\n[[case]]\nsr = -1\n").find("case[1].sr"), std::string::npos);
}

TEST(SweepSpec, LatinHypercubePutsOnePointInEveryStratum) {
  const char* text =
      "[sample]\nmethod = \"lhs\"\nn = 50\nseed = 3\nA = { min = 0.3, max = 0.8 }\n"
      "C = { min = 0.2, max = 0.4 }\nds_index = [1, 2, 3]\n";
  const SweepSpec s = parse_sweep_spec(text, "x");
  ASSERT_EQ(s.size(), 50);
  for (const auto& [key, lo, width] : {std::tuple{"A", 0.3, 0.5}, std::tuple{"C", 0.2, 0.2}}) {
    std::vector<int> hits(50, 0);
    for (std::int64_t i = 0; i < 50; ++i) {
      const RunParams p = s.run(i).params;
      const double v = std::string(key) == "A" ? p.A : p.C;
      ASSERT_GE(v, lo);
      ASSERT_LT(v, lo + width);
      ++hits[std::size_t((v - lo) / width * 50)];
    }
    for (int h : hits) EXPECT_EQ(h, 1) << key;
  }
  // The same seed gives the same points; another seed other points.
  EXPECT_EQ(parse_sweep_spec(text, "x").run(17).params.A, s.run(17).params.A);
  std::string other = text;
  other.replace(other.find("seed = 3"), 8, "seed = 4");
  EXPECT_NE(parse_sweep_spec(other, "x").run(17).params.A, s.run(17).params.A);
  const SweepSpec r = parse_sweep_spec("[sample]\nmethod = \"random\"\nn = 20\nA = { min = 1, max = 2 }\n", "x");
  for (std::int64_t i = 0; i < 20; ++i) EXPECT_TRUE(r.run(i).params.A >= 1 && r.run(i).params.A < 2);
}

TEST(SweepSpec, PermuteIndexIsABijectionOfZeroToNForAnyN) {
  for (std::uint64_t n : {1, 2, 3, 5, 64, 65, 1000, 4097}) {
    std::set<std::uint64_t> seen;
    for (std::uint64_t i = 0; i < n; ++i) {
      const std::uint64_t j = permute_index(i, n, 0x1234 + n);
      ASSERT_LT(j, n);
      seen.insert(j);
    }
    EXPECT_EQ(seen.size(), n);
  }
  // Keyed: another key, another order.
  int moved = 0;
  for (std::uint64_t i = 0; i < 1000; ++i) moved += permute_index(i, 1000, 1) != permute_index(i, 1000, 2);
  EXPECT_GT(moved, 900);
}

TEST(SweepSpec, TenMillionRunSpecIsExpandedLazily) {
  // 10^7 runs of a product and 10^7 points of a Latin hypercube: neither is
  // stored, so any run is at hand at once (memory is pinned by
  // CliPlan.TenMillionRunSpecStaysSmallInMemory).
  const SweepSpec s = parse_sweep_spec(
      "[[part]]\nname = \"grid\"\n[part.axes]\nA = { start = 0.3, stop = 0.7, num = 100 }\n"
      "B = { start = 0.1, stop = 0.8, num = 100 }\nC = { start = 0.1, stop = 0.8, num = 1000 }\n"
      "[[part]]\nname = \"lhs\"\n[part.sample]\nn = 10000000\nseed = 5\nA = { min = 0.3, max = 0.7 }\n",
      "x");
  ASSERT_EQ(s.size(), 20000000);
  EXPECT_EQ(s.run(9999999).params.C, 0.8);
  EXPECT_EQ(s.run(9999999).label, "grid");
  const RunParams last = s.run(19999999).params;
  EXPECT_TRUE(last.A >= 0.3 && last.A < 0.7) << last.A;
  EXPECT_EQ(s.run(19999999).label, "lhs");
  // The sample's first 1000 strata hold about 1000 of its points: spot-check
  // the stratification on a slice without visiting all 10^7.
  int low = 0;
  for (std::int64_t i = 0; i < 100000; ++i) low += s.run(10000000 + i).params.A < 0.3 + 0.4 * 0.01;
  EXPECT_NEAR(low, 1000, 150);
  EXPECT_EQ(s.environment_variants().size(), 2u);  // one map per part: preloading visits 2 runs, not 2e7
  // [repeat] of 10^7: no per-repeat storage either.
  const SweepSpec r = parse_sweep_spec("[fixed]\nA = 0.5\n[repeat]\ncount = 10000000\nseed = 1\n", "x");
  ASSERT_EQ(r.size(), 10000000);
  EXPECT_EQ(r.run(9999999).params.seed, repeat_seed(1, 9999999));
  EXPECT_EQ(r.axes[0].values.size(), 0u);
}

TEST(SweepSummary, MedianIsExactThenWithinItsStatedPrecisionAndMemoryIsBounded) {
  SweepSummary exact;
  for (int t : {5, 1, 4, 2}) {
    RunRow r;
    r.result.status = Status::ok;
    r.result.coverage_time = t;
    exact.add(r);
  }
  EXPECT_EQ(exact.median_time(), 3.0);
  EXPECT_TRUE(exact.median_is_exact());
  // Past the exact limit the times are binned: median within 0.05%.
  SweepSummary many;
  const std::int64_t n = std::int64_t(SweepSummary::exact_limit) * 7 / 6 + 2000;  // ok: 6 in 7
  for (std::int64_t i = 1; i <= n; ++i) {
    RunRow r;
    r.tuple.run_id = i;
    r.result.status = i % 7 ? Status::ok : Status::timeout;
    r.result.coverage_time = 1000.0 + double(i) * 1e-3;
    many.add(r);
  }
  EXPECT_FALSE(many.median_is_exact());
  std::vector<double> ok;
  for (std::int64_t i = 1; i <= n; ++i)
    if (i % 7) ok.push_back(1000.0 + double(i) * 1e-3);
  const double truth = ok.size() % 2 ? ok[ok.size() / 2] : 0.5 * (ok[ok.size() / 2 - 1] + ok[ok.size() / 2]);
  EXPECT_NEAR(many.median_time(), truth, truth * 5e-4);
  EXPECT_EQ(many.best_time(), 1000.001);
  EXPECT_EQ(many.best_run_id(), 1);
  EXPECT_EQ(many.count(Status::timeout), n / 7);
  EXPECT_NE(many.text().find("within 0.05%"), std::string::npos);
}

TEST(SweepSpec, RepeatsDeriveEachRunsSeedFromMasterSeedAndRunId) {
  const SweepSpec s = parse_sweep_spec("[axes]\nA = [0.4, 0.5]\n[repeat]\ncount = 4\nseed = 99\n", "x");
  ASSERT_EQ(s.size(), 8);
  std::set<std::int64_t> seeds;
  for (std::int64_t i = 0; i < 8; ++i) {
    EXPECT_EQ(s.run(i).params.seed, repeat_seed(99, i));
    seeds.insert(s.run(i).params.seed);
  }
  EXPECT_EQ(seeds.size(), 8u);
  EXPECT_EQ(s.run(5).params.A, 0.5);
  EXPECT_LT(repeat_seed(99, 5), std::int64_t(1) << 53);
  EXPECT_NE(error_of("[fixed]\nseed = 3\n[repeat]\ncount = 2\n").find("'seed' must not be given"), std::string::npos);
  EXPECT_NE(error_of("[sample]\nn = 5\nds_index = { min = 1, max = 3 }\n").find("give a list"), std::string::npos);
  EXPECT_NE(error_of("[sample]\nA = { min = 1, max = 2 }\n").find("sample.n"), std::string::npos);
  EXPECT_NE(error_of("[sample]\nn = 3\nmethod = \"sobol\"\nA = [1]\n").find("lhs"), std::string::npos);
}

TEST(SweepSpec, ExtendsAnotherSpecAndAddsAxes) {
  TempDir tmp;
  write_file(tmp.file("base.toml"), "[fixed]\nsr = 4\nsize = 20\n[axes]\nA = [0.4, 0.5]\n");
  write_file(tmp.file("more.toml"),
             "[sweep]\nextends = \"base.toml\"\n[fixed]\nsr = 2\n[axes]\nseed = { start = 0, stop = 2, step = 1 }\n");
  const SweepSpec s = load_sweep_spec(tmp.file("more.toml"));
  EXPECT_EQ(s.size(), 6);
  EXPECT_EQ(s.base.params.sr, 2.0);  // the extending spec's fixed value wins
  EXPECT_EQ(s.base.params.size_x, 20.0);
  EXPECT_EQ(s.run(5).params.A, 0.5);
  EXPECT_EQ(s.run(5).params.seed, 2);
  EXPECT_NE(s.text.find("A = [0.4, 0.5]"), std::string::npos);  // provenance holds both files
  write_file(tmp.file("clash.toml"), "[sweep]\nextends = \"base.toml\"\n[fixed]\nA = 1\n");
  EXPECT_THROW(load_sweep_spec(tmp.file("clash.toml")), SpecError);
}

TEST(SweepSpec, AcceptsAliasesAndTuples) {
  const SweepSpec s =
      parse_sweep_spec("[fixed]\nsize = [40, 30]\nic = [0.1, 0.2, 0.3]\n[axes]\nstart = [[1, 1], [2, 3]]\n", "x");
  const RunParams p = s.run(1).params;
  EXPECT_EQ(p.size_x, 40.0);
  EXPECT_EQ(p.size_y, 30.0);
  EXPECT_EQ(p.ic_z, 0.3);
  EXPECT_EQ(p.start_x, 2.0);
  EXPECT_EQ(p.start_y, 3.0);
}

TEST(SweepSpec, ErrorsNameTheKeyAndTheAllowedRange) {
  EXPECT_NE(error_of("[fixed]\nsr = 0\n").find("fixed.sr"), std::string::npos);
  EXPECT_NE(error_of("[fixed]\nsr = 0\n").find("[0.001, 10000]"), std::string::npos);
  EXPECT_NE(error_of("[fixed]\nfoo = 1\n").find("unknown key 'foo'"), std::string::npos);
  EXPECT_NE(error_of("[axes]\nds_index = [1, 2, 5]\n").find("axes.ds_index[2]"), std::string::npos);
  EXPECT_NE(error_of("[axes]\nA = []\n").find("axes.A: is empty"), std::string::npos);
  EXPECT_NE(error_of("[axes]\nA = { start = 0, stop = 1 }\n").find("step or num"), std::string::npos);
  EXPECT_NE(error_of("[axes]\nA = { start = 0, stop = 1, nun = 3 }\n").find("'nun'"), std::string::npos);
  EXPECT_NE(error_of("[fixed]\nboundary = \"wall\"\n").find("mirror, fold"), std::string::npos);
  EXPECT_NE(error_of("[fixed]\nA = \"big\"\n").find("must be a number"), std::string::npos);
  EXPECT_NE(error_of("[runs]\n").find("unknown section 'runs'"), std::string::npos);
  EXPECT_NE(error_of("[fixed]\nA = 1\n[axes]\nA = [1, 2]\n").find("one place"), std::string::npos);
  EXPECT_NE(error_of("[[zip]]\nA = [1, 2]\nB = [1]\n").find("equal lengths"), std::string::npos);
  EXPECT_NE(error_of("[[zip]]\nA = [1, 2]\nsr = [1, 0]\n").find("zip[0].sr[1]"), std::string::npos);
  EXPECT_NE(error_of("[fixed\n").find("line 1"), std::string::npos);
}

// Three parts over one base, with a shared seed axis (2 values) after each part's own axes.
const char* parts_spec = R"(
[fixed]
size = 12
sr = 1
max_time = 3000
[axes]
seed = [0, 1]

[[part]]
name = "original"
[part.axes]
ds_index = [1, 2, 3]

[[part]]
name = "zoning"
case = [ { label = "z1", c = 0.5 }, { c = 0.75 } ]
[part.fixed]
map_zoning = 1
[part.axes]
f = [1, 2]

[[part]]
name = "logistic"
fixed = { planner = "logistic" }
)";

TEST(SweepSpecParts, SizesAddUpAndRunIdsFollowThePartsInFileOrder) {
  const SweepSpec s = parse_sweep_spec(parts_spec, "spec.toml");
  ASSERT_EQ(s.parts.size(), 3u);
  EXPECT_EQ(s.parts[0].name, "original");
  EXPECT_EQ(s.parts[2].name, "logistic");
  EXPECT_EQ(s.part_size(0), 3 * 2);
  EXPECT_EQ(s.part_size(1), 2 * 2 * 2);
  EXPECT_EQ(s.part_size(2), 1 * 2);  // no axes of its own: one point, times the shared axes
  EXPECT_EQ(s.size(), 6 + 8 + 2);
  EXPECT_EQ(s.part_offset(1), 6);
  EXPECT_EQ(s.part_offset(2), 14);
  EXPECT_EQ(s.part_of(0), 0u);
  EXPECT_EQ(s.part_of(5), 0u);
  EXPECT_EQ(s.part_of(6), 1u);
  EXPECT_EQ(s.part_of(15), 2u);
  EXPECT_THROW(s.part_of(16), std::out_of_range);
}

TEST(SweepSpecParts, FirstAndLastRunOfEachPartHaveThatPartsSettings) {
  const SweepSpec s = parse_sweep_spec(parts_spec, "spec.toml");
  // Part 0: ds_index slowest, then the shared seed.
  RunSpec r = s.run(0);
  EXPECT_EQ(r.params.ds_index, 1);
  EXPECT_EQ(r.params.seed, 0);
  EXPECT_EQ(r.params.map_zoning, 0);
  EXPECT_EQ(r.params.size_x, 12.0);  // every part starts from the top-level base
  r = s.run(5);
  EXPECT_EQ(r.params.ds_index, 3);
  EXPECT_EQ(r.params.seed, 1);
  // Part 1: its fixed settings, then case (slowest), f, seed.
  r = s.run(6);
  EXPECT_EQ(r.params.map_zoning, 1);
  EXPECT_EQ(r.params.c, 0.5);
  EXPECT_EQ(r.params.f, 1.0);
  EXPECT_EQ(r.params.seed, 0);
  EXPECT_EQ(r.params.ds_index, RunParams{}.ds_index);  // part 0's axis does not leak
  r = s.run(13);
  EXPECT_EQ(r.params.map_zoning, 1);
  EXPECT_EQ(r.params.c, 0.75);
  EXPECT_EQ(r.params.f, 2.0);
  EXPECT_EQ(r.params.seed, 1);
  // Part 2: fixed only.
  r = s.run(14);
  EXPECT_EQ(r.params.planner, Planner::logistic);
  EXPECT_EQ(r.params.seed, 0);
  EXPECT_EQ(r.params.map_zoning, 0);  // part 1's fixed setting does not leak
  r = s.run(15);
  EXPECT_EQ(r.params.planner, Planner::logistic);
  EXPECT_EQ(r.params.seed, 1);
  EXPECT_EQ(s.text, parts_spec);  // provenance is the whole file
}

TEST(SweepSpecParts, TopLevelAxesVaryFastestInEveryPart) {
  const SweepSpec s = parse_sweep_spec(parts_spec, "spec.toml");
  for (std::size_t k = 0; k < s.parts.size(); ++k) {
    const std::int64_t first = s.part_offset(k);
    for (std::int64_t i = first; i < first + s.part_size(k); ++i) EXPECT_EQ(s.run(i).params.seed, (i - first) % 2);
  }
  // [repeat] seeds follow the global run_id, across parts.
  const SweepSpec r = parse_sweep_spec(
      "[repeat]\ncount = 3\nseed = 5\n[[part]]\nname = \"a\"\naxes = { A = [0.4, 0.5] }\n"
      "[[part]]\nname = \"b\"\n",
      "spec.toml");
  ASSERT_EQ(r.size(), 2 * 3 + 3);
  for (std::int64_t i = 0; i < r.size(); ++i) EXPECT_EQ(r.run(i).params.seed, repeat_seed(5, i));
  EXPECT_EQ(r.run(5).params.A, 0.5);
  EXPECT_EQ(r.run(6).label, "b");
}

TEST(SweepSpecParts, LabelDefaultsToThePartNameUnlessTheSpecGivesOne) {
  const SweepSpec s = parse_sweep_spec(parts_spec, "spec.toml");
  EXPECT_EQ(s.run(0).label, "original");
  EXPECT_EQ(s.run(6).label, "z1");       // a case's label wins
  EXPECT_EQ(s.run(10).label, "zoning");  // the case without one gets the part's name
  EXPECT_EQ(s.run(15).label, "logistic");
  const SweepSpec f = parse_sweep_spec("[fixed]\nlabel = \"all\"\n[[part]]\nname = \"p\"\n", "x");
  EXPECT_EQ(f.run(0).label, "all");  // so does a fixed label
  const SweepSpec g = parse_sweep_spec("[[part]]\nname = \"p\"\nfixed = { label = \"mine\" }\n", "x");
  EXPECT_EQ(g.run(0).label, "mine");
}

TEST(SweepSpecParts, BadPartsFailNamingTheLocation) {
  const std::string part = "[[part]]\nname = \"a\"\n";
  // A key set twice: top-level fixed and part, or twice in one part.
  EXPECT_NE(error_of("[fixed]\nsr = 2\n" + part + "[part.fixed]\nsr = 1\n")
                .find("spec.toml: part[0].fixed.sr: is also set in fixed.sr"),
            std::string::npos);
  EXPECT_NE(error_of("[fixed]\nsr = 2\n" + part + "[part.axes]\nsr = [1, 2]\n").find("part[0].axes.sr"),
            std::string::npos);
  EXPECT_NE(error_of(part + "[part.fixed]\nc = 0.5\n[part.axes]\nc = [0.1]\n")
                .find("part[0].axes.c: is also set in part[0].fixed.c"),
            std::string::npos);
  EXPECT_NE(error_of(part + "[part.axes]\nc = [0.1]\n[[part.zip]]\nc = [0.2]\n").find("one place"), std::string::npos);
  // The same key in two parts is fine: each part is its own product.
  EXPECT_EQ(error_of(part + "axes = { c = [0.1] }\n[[part]]\nname = \"b\"\naxes = { c = [0.2, 0.3] }\n"), "");
  // Unknown keys, values, a missing or repeated name.
  const std::string unknown = error_of(part + "[part.repeat]\ncount = 2\n");
  EXPECT_NE(unknown.find("spec.toml: part[0]: unknown key 'repeat'"), std::string::npos);
  EXPECT_NE(unknown.find("allowed: name, fixed, axes, zip, case, sample"), std::string::npos);
  EXPECT_NE(error_of(part + "extends = \"x.toml\"\n").find("unknown key 'extends'"), std::string::npos);
  EXPECT_NE(error_of(part + "[[part.part]]\nname = \"b\"\n").find("parts do not nest"), std::string::npos);
  EXPECT_NE(
      error_of(part + "[[part]]\nname = \"b\"\n[part.axes]\nsr = [0.5, 0]\n").find("spec.toml: part[1].axes.sr[1]"),
      std::string::npos);
  EXPECT_NE(error_of(part + "[part.axes]\nfoo = [1]\n").find("part[0].axes.foo[0]: unknown key 'foo'"),
            std::string::npos);
  EXPECT_NE(error_of(part + "case = [ { sr = 1 }, { sr = -1 } ]\n").find("part[0].case[1].sr"), std::string::npos);
  EXPECT_NE(error_of("[[part]]\naxes = { c = [0.1] }\n").find("spec.toml: part[0]: needs a name"), std::string::npos);
  EXPECT_NE(error_of(part + part).find("spec.toml: part[1].name"), std::string::npos);
  EXPECT_NE(error_of("part = 3\n").find("[[part]] tables"), std::string::npos);
}

TEST(SweepSpecParts, APartMustNotSetAKeyOfATopLevelAxis) {
  const std::string part = "[[part]]\nname = \"a\"\n";
  const std::string e = error_of("[axes]\nseed = [0, 1]\n" + part + "[part.axes]\nseed = [3]\n");
  EXPECT_NE(e.find("spec.toml: part[0].axes.seed: is a top-level axis (axes.seed)"), std::string::npos) << e;
  EXPECT_NE(error_of("[axes]\nseed = [0, 1]\n" + part + "[part.fixed]\nseed = 3\n").find("top-level axis"),
            std::string::npos);
  EXPECT_NE(error_of("case = [ { c = 0.1 } ]\n" + part + "[part.axes]\nc = [0.5]\n").find("top-level axis (case)"),
            std::string::npos);
  EXPECT_NE(error_of("[repeat]\ncount = 2\n" + part + "[part.axes]\nseed = [1, 2]\n").find("top-level axis (repeat)"),
            std::string::npos);
}

TEST(SweepSpecParts, ExtendingASpecKeepsItsPartsAndAppendsNewOnes) {
  TempDir tmp;
  write_file(tmp.file("base.toml"), "[fixed]\nsr = 4\nsize = 20\n[[part]]\nname = \"a\"\naxes = { A = [0.4, 0.5] }\n");
  write_file(tmp.file("more.toml"),
             "[sweep]\nextends = \"base.toml\"\n[fixed]\nsr = 2\n[axes]\nseed = [0, 1, 2]\n"
             "[[part]]\nname = \"b\"\nfixed = { A = 0.6 }\n");
  const SweepSpec s = load_sweep_spec(tmp.file("more.toml"));
  ASSERT_EQ(s.parts.size(), 2u);
  EXPECT_EQ(s.size(), 2 * 3 + 3);
  EXPECT_EQ(s.run(5).params.A, 0.5);
  EXPECT_EQ(s.run(5).params.seed, 2);
  EXPECT_EQ(s.run(5).params.sr, 2.0);  // the extending spec's base holds for the inherited parts
  EXPECT_EQ(s.run(8).params.A, 0.6);
  EXPECT_EQ(s.run(8).label, "b");
  write_file(tmp.file("clash.toml"), "[sweep]\nextends = \"base.toml\"\n[fixed]\nA = 0.3\n");
  EXPECT_THROW(load_sweep_spec(tmp.file("clash.toml")), SpecError);
  write_file(tmp.file("twice.toml"), "[sweep]\nextends = \"base.toml\"\n[[part]]\nname = \"a\"\n");
  EXPECT_THROW(load_sweep_spec(tmp.file("twice.toml")), SpecError);
}

TEST(SweepSpec, DemoSpecIsAFewHundredRunsOfTheOriginalPlanner) {
  const SweepSpec s = load_sweep_spec(std::string(CHAOSWEEP_SOURCE_DIR) + "/experiments/demo.toml");
  EXPECT_EQ(s.name, "demo");
  EXPECT_EQ(s.size(), 7 * 8 * 5);
  EXPECT_EQ(s.base.params.planner, Planner::arnold);
  EXPECT_EQ(s.base.params.sr, 4.0);
  EXPECT_EQ(s.base.params.size_x, 50.0);
}

TEST(SweepSpec, Table1SearchSpecsHaveOnePartPerTechniqueSet) {
  const std::string dir = std::string(CHAOSWEEP_SOURCE_DIR) + "/experiments/";
  const SweepSpec coarse = load_sweep_spec(dir + "table1_search.toml");
  const SweepSpec fine = load_sweep_spec(dir + "table1_search_fine.toml");
  EXPECT_EQ(coarse.size(), 97760);
  EXPECT_EQ(fine.size(), 363488);
  for (const SweepSpec* s : {&coarse, &fine}) {
    ASSERT_EQ(s->parts.size(), 9u);
    EXPECT_EQ(s->parts[7].name, "MZ+SC");
    // Each part's first run is its first Table 1 row; seeds vary fastest.
    const char* first_rows[] = {"1", "11", "12", "20", "24", "28", "36", "40", "44"};
    for (std::size_t k = 0; k < 9; ++k) {
      const RunSpec r = s->run(s->part_offset(k));
      EXPECT_EQ(r.label, first_rows[k]) << s->name << " part " << k;
      EXPECT_EQ(r.params.seed, 0);
      EXPECT_EQ(r.params.ic_jitter, 1e-6);
      EXPECT_EQ(r.params.max_pr, 50.0);
    }
    const RunSpec last = s->run(s->size() - 1);
    EXPECT_EQ(last.label, "47");
    EXPECT_EQ(last.params.seed, 31);
    EXPECT_EQ(last.params.ds_index, 3);
    EXPECT_EQ(last.params.c, 1.0);
    EXPECT_EQ(last.params.f, 6.0);
    EXPECT_EQ(last.params.index_switching, 1);
    EXPECT_EQ(last.params.map_zoning, 1);
  }
}

// ------------------------------------------------------------ environments

TEST(Environment, LoadsRelativeObstaclesScaledToTheMap) {
  TempDir tmp;
  write_file(tmp.file("one.toml"),
             "name = \"one\"\nunits = \"relative\"\nstart = [0.5, 0.5]\nstart_units = \"m\"\n"
             "obstacles = [{ x = 0.3, y = 0.3, w = 0.4, h = 0.4 }]\n");
  const Environment e = load_environment(tmp.file("one.toml"), 100.0, 100.0);
  EXPECT_EQ(e.name, "one");
  ASSERT_EQ(e.obstacles.size(), 1u);
  EXPECT_DOUBLE_EQ(e.obstacles[0].x0, 30.0);
  EXPECT_DOUBLE_EQ(e.obstacles[0].x1, 70.0);
  EXPECT_DOUBLE_EQ(e.obstacle_area(), 1600.0);
  EXPECT_EQ(e.start->first, 0.5);
}

TEST(Environment, MetreFilesFixTheirOwnSize) {
  TempDir tmp;
  write_file(tmp.file("m.toml"), "units = \"m\"\nsize = [20, 10]\nobstacles = [{x=1,y=1,w=2,h=2}]\n");
  const Environment e = load_environment(tmp.file("m.toml"), 50.0, 50.0);
  EXPECT_EQ(e.lx, 20.0);
  EXPECT_EQ(e.ly, 10.0);
  EXPECT_EQ(e.obstacles[0].x1, 3.0);
}

// A thread remembers the last environment each cache gave it (no lock per
// run): the same entry for the same key, on every thread; another key or
// another cache looks it up again, so a cache made after the file changed
// reads the new file.
TEST(EnvironmentCache, GivesOneEntryPerKeyOnEveryThreadAndNeverAnotherCachesEntry) {
  TempDir tmp;
  write_file(tmp.file("m.toml"), "units = \"m\"\nsize = [20, 10]\nobstacles = [{x=1,y=1,w=2,h=2}]\n");
  EnvironmentCache cache;
  const auto a = cache.get(tmp.file("m.toml"), 50, 50);
  EXPECT_EQ(cache.get(tmp.file("m.toml"), 50, 50).get(), a.get());
  const auto empty = cache.get("empty", 50, 50);
  EXPECT_NE(empty.get(), a.get());
  EXPECT_NE(cache.get("empty", 40, 50).get(), empty.get());
  EXPECT_EQ(cache.get("empty", 50, 50).get(), empty.get());
  EXPECT_EQ(cache.get(tmp.file("m.toml"), 50, 50).get(), a.get());
  const Environment* on_other_thread = nullptr;
  std::thread([&] { on_other_thread = cache.get(tmp.file("m.toml"), 50, 50).get(); }).join();
  EXPECT_EQ(on_other_thread, a.get());
  write_file(tmp.file("m.toml"), "units = \"m\"\nsize = [20, 10]\nobstacles = [{x=1,y=1,w=3,h=2}]\n");
  EnvironmentCache later;
  const auto b = later.get(tmp.file("m.toml"), 50, 50);
  EXPECT_EQ(a->obstacles[0].x1, 3.0);
  EXPECT_EQ(b->obstacles[0].x1, 4.0);
  EXPECT_EQ(cache.get(tmp.file("m.toml"), 50, 50).get(), a.get());  // each cache keeps its own
}

TEST(Environment, MalformedFilesGiveErrorsNamingTheKey) {
  TempDir tmp;
  auto error = [&](const std::string& text) -> std::string {
    write_file(tmp.file("bad.toml"), text);
    try {
      load_environment(tmp.file("bad.toml"), 50, 50);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error("colour = 1\n").find("unknown key 'colour'"), std::string::npos);
  EXPECT_NE(error("units = \"m\"\n").find("'size' is required"), std::string::npos);
  EXPECT_NE(error("obstacles = [{x=1,y=1,w=2}]\n").find("obstacles[0] lacks 'h'"), std::string::npos);
  EXPECT_NE(error("obstacles = [{x=1,y=1,w=-2,h=1}]\n").find("positive"), std::string::npos);
  EXPECT_NE(error("obstacles = [\n").find("line"), std::string::npos);
  EXPECT_THROW(load_environment("no_such_environment", 50, 50), std::runtime_error);
}

// ------------------------------------------------------------------ runner

TEST(SweepRunner, RowsDoNotDependOnThreadsOrBatches) {
  const SweepSpec s = parse_sweep_spec(small_spec, "spec.toml");
  SweepOptions odd_batches;
  odd_batches.batch_size = 7;
  const ThreadBatchEvaluator one(1), two(2);
  const auto a = sweep_rows(s, one), b = sweep_rows(s, two), c = sweep_rows(s, two, odd_batches);
  std::string diff;
  EXPECT_TRUE(same_rows(a, b, diff)) << diff;
  EXPECT_TRUE(same_rows(a, c, diff)) << diff;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].tuple.run_id, std::int64_t(i));
  int ok = 0;
  for (const RunRow& r : a) ok += r.result.status == Status::ok;
  EXPECT_GT(ok, 0);
}

TEST(SweepRunner, ShardsOfASpecWithPartsTileItsRunIds) {
  const SweepSpec s = parse_sweep_spec(parts_spec, "spec.toml");
  SweepOptions all, shard;
  shard.shard_index = 1;
  shard.shard_count = 3;
  const auto a = sweep_rows(s, all), b = sweep_rows(s, shard);
  ASSERT_EQ(a.size(), std::size_t(s.size()));
  for (const RunRow& r : a) {
    const RunSpec want = s.run(r.tuple.run_id);
    EXPECT_EQ(r.tuple.label, want.label);
    EXPECT_EQ(r.tuple.params.planner, want.params.planner);
    EXPECT_EQ(r.tuple.params.c, want.params.c);
  }
  ASSERT_EQ(b.size(), std::size_t(shard_size(s.size(), 1, 3)));
  std::vector<RunRow> expected;
  for (std::size_t j = 0; j < b.size(); ++j) expected.push_back(a[std::size_t(shard_run_id(std::int64_t(j), 1, 3))]);
  std::string diff;
  EXPECT_TRUE(same_rows(expected, b, diff)) << diff;
}

TEST(SweepRunner, AnInvalidRunIsRecordedAndTheSweepGoesOn) {
  TempDir tmp;
  write_file(tmp.file("box.toml"), "obstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n");
  const SweepSpec s = parse_sweep_spec("[fixed]\nsize = 10\nenv = \"" + tmp.file("box.toml") +
                                           "\"\ndc = 0.3\n[axes]\nstart = [[1, 1], [5, 5], [9, 9]]\n",
                                       "x");
  const auto rows = sweep_rows(s);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].result.status, Status::ok);
  EXPECT_EQ(rows[1].result.status, Status::invalid);
  EXPECT_NE(rows[1].result.message.find("inside obstacle"), std::string::npos);
  EXPECT_EQ(rows[2].result.status, Status::ok);
}

TEST(SweepRunner, RowsAreBitIdenticalAcrossWidthsThreadsAndBatches) {
  // Every technique set, both boundaries (also with steps longer than the
  // map, which the lanes fold in full, and on the mirror boundary among
  // obstacles, whose lanes reflect once and leave the rest to the sink;
  // steps of 0.2-0.3 cells, which the lanes take into a diagonal neighbour
  // themselves), obstacles (with and without map
  // zoning, under both boundaries, every obstacle response; a map of many,
  // indexed; obstacles closer than 2 fo, whose margins overlap), the Logistic
  // planner (its own lanes: jitter, fold, points, a stuck end, an orbit that
  // reaches a fixed point at its second point), the scalar-only paths (step
  // doubling, Chebyshev), a run outside small-shift mode (dt = 0.5),
  // an invalid run and the flows and maps of kernels/systems/ (each system's
  // runs in lanes of their own), mixed in one batch.
  const SweepSpec s = parse_sweep_spec(R"(
case = [
  { label = "original" },
  { label = "fold", boundary = "fold" },
  { label = "fold-long-steps", boundary = "fold", f = 200 },
  { label = "mirror-long-steps", f = 200 },
  { label = "obstacles", env = "five_squares", start = [4.8, 1.6] },
  { label = "obstacles-fold", boundary = "fold", env = "one_square", start = [1, 8] },
  { label = "is", index_switching = 1, ds_index = 1 },
  { label = "mz", map_zoning = 1, c = 0.8, env = "five_squares", start = [4.8, 1.6] },
  { label = "mz-open", map_zoning = 1, c = 0.8 },
  { label = "mz-is-sc", map_zoning = 1, index_switching = 1, c = 0.5, f = 1.7, env = "one_square" },
  { label = "jitter", ic_jitter = 1e-6, seed = 3 },
  { label = "doubling", integrator = "rk4-doubling" },
  { label = "logistic", planner = "logistic" },
  { label = "chebyshev", planner = "chebyshev", env = "one_square", start = [1, 8] },
  { label = "invalid", env = "one_square", start = [8, 8] },
  { label = "points", sampling = "points", f = 4 },
  { label = "mz-points", sampling = "points", map_zoning = 1, c = 0.8 },
  { label = "mz-points-distance-first", sampling = "points", map_zoning = 1, c = 0.8, zone_order = "distance" },
  { label = "full-trig", dt = 0.5 },
  { label = "obstacles-mirror", obstacle_response = "mirror", env = "five_squares", start = [4.8, 1.6] },
  { label = "obstacles-bounce", obstacle_response = "reflect", env = "five_squares", start = [4.8, 1.6] },
  { label = "bounce-fold-mz", obstacle_response = "reflect", boundary = "fold", map_zoning = 1, c = 0.8, env = "one_square", start = [1, 8] },
  { label = "mz-density-first", map_zoning = 1, c = 0.8, zone_order = "density", env = "five_squares", start = [4.8, 1.6] },
  { label = "mz-replan-reuse", map_zoning = 1, c = 0.8, transit_replan = "reuse", env = "five_squares", start = [4.8, 1.6] },
  { label = "mz-logistic-reset", map_zoning = 1, c = 0.8, zone_goal = "midpoint", logistic_reset = "drop", env = "five_squares", start = [4.8, 1.6] },
  { label = "all-cells", coverage_cells = "all", env = "five_squares", start = [4.8, 1.6] },
  { label = "mz-all-cells", map_zoning = 1, c = 0.8, coverage_cells = "all", env = "one_square", start = [1, 8] },
  { label = "mz-transit-distance", map_zoning = 1, c = 0.8, transit_time = "distance", env = "five_squares", start = [4.8, 1.6] },
  { label = "clutter", env = "clutter" },
  { label = "mz-clutter", map_zoning = 1, c = 0.8, env = "clutter", start = [8, 8] },
  { label = "packed-obstacles", fo = 0.8, env = "five_squares", start = [8, 1] },
  { label = "diagonal-steps", f = 3 },
  { label = "diagonal-mz-obstacles", f = 2, map_zoning = 1, c = 0.8, env = "five_squares", start = [4.8, 1.6] },
  { label = "diagonal-fold-mz", f = 2.5, boundary = "fold", map_zoning = 1, c = 0.8, env = "one_square", start = [1, 8] },
  { label = "diagonal-logistic", planner = "logistic", dt_c = 0.3, env = "five_squares", start = [4.8, 1.6] },
  { label = "obstacles-long-steps", f = 200, env = "five_squares", start = [4.8, 1.6] },
  { label = "lorenz", system = "lorenz", dt = 0.001, f = 100 },
  { label = "lorenz-fold-y", system = "lorenz", boundary = "fold", dt = 0.001, f = 100, ds_index = 2 },
  { label = "chen-obstacles", system = "chen", dt = 0.001, f = 100, env = "five_squares", start = [4.8, 1.6] },
  { label = "chua-mz-is", system = "chua", sys_a = 9.5, index_switching = 1, map_zoning = 1, c = 0.8, dt = 0.002, f = 50, ds_index = 1, env = "one_square", start = [1, 8] },
  { label = "chirikov", system = "chirikov", ds_index = 1, dt = 1 },
  { label = "chirikov-is-obstacles", system = "chirikov", ds_index = 2, index_switching = 1, dt = 0.5, env = "five_squares", start = [4.8, 1.6] },
  { label = "logistic-obstacles-jitter", planner = "logistic", logistic_jitter = 1e-6, seed = 5, v = 0.9, dt_c = 0.07, env = "five_squares", start = [4.8, 1.6] },
  { label = "logistic-fold-points", planner = "logistic", boundary = "fold", sampling = "points", env = "one_square", start = [1, 8] },
  { label = "logistic-mirror-stuck", planner = "logistic", obstacle_response = "mirror", stuck_time = 40, env = "five_squares", start = [4.8, 1.6] },
  { label = "logistic-fixed-point", planner = "logistic", logistic_x0 = 0.5 },
]
[fixed]
size = 16
sr = 1
max_time = 1500
niter = 200
[axes]
A = [0.45, 0.5]
)",
                                       "x");
  EnvironmentCache cache;
  std::vector<RunTuple> tuples;
  for (std::int64_t i = 0; i < s.size(); ++i) tuples.push_back(resolve_run(i, s.run(i), cache));
  // The scalar reference: one PlannerRun per run, no lanes.
  std::vector<RunRow> reference;
  for (const RunTuple& t : tuples) reference.push_back({t, SerialBatchEvaluator().evaluate(t)});
  int compared = 0;
  for (SimdTarget target : {SimdTarget::scalar, SimdTarget::avx2, SimdTarget::avx512}) {
    if (!cpu_supports(target)) continue;  // widths this CPU cannot run are tested where it can
    for (int threads : {1, 2})
      for (std::int64_t batch : {1, 7, 4096}) {
        const ThreadBatchEvaluator lanes(threads, target);
        std::vector<RunRow> rows;
        for (std::size_t first = 0; first < tuples.size(); first += std::size_t(batch)) {
          const std::size_t n = std::min(tuples.size() - first, std::size_t(batch));
          std::vector<RunResult> results(n);
          EXPECT_EQ(lanes.evaluate(std::span(tuples).subspan(first, n), results), n);
          for (std::size_t k = 0; k < n; ++k) rows.push_back({tuples[first + k], results[k]});
        }
        std::string diff;
        EXPECT_TRUE(same_rows(reference, rows, diff))
            << to_string(target) << ", " << threads << " threads, batches of " << batch << ": " << diff;
        ++compared;
      }
  }
  EXPECT_GE(compared, 6);
  int ok = 0;
  for (const RunRow& r : reference) ok += r.result.status == Status::ok;
  EXPECT_GT(ok, 5);  // most of these runs reach dc: the comparison covers whole runs
  EXPECT_EQ(reference[28].result.status, Status::invalid);                             // case 14 of 17, A = 0.45
  EXPECT_EQ(reference[26].result.status, Status::ok) << reference[26].result.message;  // the Chebyshev run
  const auto labelled = [&](std::string_view label) {
    return std::find_if(reference.begin(), reference.end(), [&](const RunRow& r) { return r.tuple.label == label; })
        ->result;
  };
  EXPECT_EQ(labelled("logistic-fixed-point").status, Status::diverged);  // x0 = 0.5: x1 = 1, x2 = 0
  EXPECT_EQ(labelled("logistic-fixed-point").steps, 1);
  EXPECT_EQ(labelled("logistic-mirror-stuck").status, Status::stuck);
  // The flows' and maps' runs (the six cases before the Logistic ones,
  // mixed with Arnold runs in every batch: the lanes take one system at a
  // time): the Lorenz and Chirikov ones reach dc, the others run to the
  // budget; both compare whole runs.
  int systems_ok = 0;
  for (std::size_t i = reference.size() - 20; i < reference.size() - 8; ++i) {
    systems_ok += reference[i].result.status == Status::ok;
    EXPECT_GT(reference[i].result.visited_cells, 40) << reference[i].tuple.label;
  }
  EXPECT_GE(systems_ok, 6);
}

// Every combination of the map-zoning options and the sampling (192 runs,
// with obstacles and without): the lanes at the CPU's widest width give
// each run's row bit for bit as the scalar reference does. Found the lanes'
// window stamps under sampling = points, which only some of these
// combinations showed.
TEST(SweepRunner, LanesMatchTheReferenceForEveryMapZoningOptionCombination) {
  const SweepSpec s = parse_sweep_spec(R"(
[fixed]
size = 16
sr = 1
max_time = 1500
niter = 200
c = 0.8
map_zoning = 1
start = [4.8, 1.6]
[axes]
sampling = ["points", "segments"]
transit_replan = ["fresh", "reuse"]
transit_time = ["points", "distance"]
zone_order = ["auto", "density", "distance"]
zone_goal = ["free", "midpoint"]
logistic_reset = ["never", "drop"]
env = ["empty", "five_squares"]
)",
                                       "x");
  ASSERT_EQ(s.size(), 192);
  const std::vector<RunRow> reference = sweep_rows(s, SerialBatchEvaluator());
  const std::vector<RunRow> lanes = sweep_rows(s, ThreadBatchEvaluator(2));
  ASSERT_EQ(lanes.size(), 192u);
  std::string diff;
  EXPECT_TRUE(same_rows(reference, lanes, diff)) << diff;
  int zoned = 0;
  for (const RunRow& r : reference) zoned += r.result.zonings > 0;
  EXPECT_GT(zoned, 150);  // the options are exercised: nearly every run zones
}

TEST(SimdChoice, HonoursAndChecksChaosweepSimd) {
  setenv("CHAOSWEEP_SIMD", "scalar", 1);
  EXPECT_EQ(selected_simd_target(), SimdTarget::scalar);
  setenv("CHAOSWEEP_SIMD", "avx3", 1);
  EXPECT_THROW(selected_simd_target(), std::runtime_error);
  unsetenv("CHAOSWEEP_SIMD");
  EXPECT_EQ(selected_simd_target(), best_simd_target());
}

TEST(Progress, LineShowsDoneTotalRateEtaAndFailures) {
  EXPECT_EQ(ProgressReporter::line(250, 1000, 12, 10.0), "250/1000 runs (25.0%), 25 runs/s, ETA 30s, 12 not ok");
  EXPECT_EQ(ProgressReporter::line(1000, 1000, 0, 100.0), "1000/1000 runs (100.0%), 10 runs/s, ETA 0s, 0 not ok");
  EXPECT_EQ(ProgressReporter::line(10, 100000, 0, 1.0), "10/100000 runs (0.0%), 10 runs/s, ETA 2h46m, 0 not ok");
}

// On a narrow terminal the live line gets terser, never longer than the
// width minus one (a line that reaches the last column may wrap).
TEST(Progress, LineFitsTheTerminalWidth) {
  EXPECT_EQ(ProgressReporter::line(250, 1000, 12, 10.0, 80), "250/1000 runs (25.0%), 25 runs/s, ETA 30s, 12 not ok");
  EXPECT_EQ(ProgressReporter::line(250, 1000, 12, 10.0, 50), "250/1000 25.0% 25/s ETA 30s 12 not ok");
  EXPECT_EQ(ProgressReporter::line(250, 1000, 12, 10.0, 25), "250/1000 25.0% ETA 30s");
  EXPECT_EQ(ProgressReporter::line(250, 1000, 12, 10.0, 16), "25.0% ETA 30s");
  EXPECT_EQ(ProgressReporter::line(250, 1000, 12, 10.0, 8), "25.0% E");
  for (int width : {1, 2, 10, 20, 30, 40, 50, 60, 80, 200})
    for (const auto& [done, total, failed, s] : {std::tuple{0LL, 0LL, 0LL, 0.0},
                                                 {123456789LL, 9876543210LL, 4567890LL, 86400.0 * 30},
                                                 {5LL, 7LL, 0LL, 1e-6},
                                                 {999999LL, 1000000LL, 999999LL, 3.5}}) {
      const std::string line = ProgressReporter::line(done, total, failed, s, width);
      EXPECT_LT(int(line.size()), std::max(width, 1)) << width << ": " << line;
      EXPECT_FALSE(line.empty() && width > 1) << width;
    }
}

TEST(SweepSummary, StatesTheElapsedWallClockTime) {
  SweepSummary s;
  RunRow row;
  row.result.status = Status::ok;
  row.result.coverage_time = 1234.5;
  s.add(row);
  EXPECT_EQ(s.text().find("elapsed"), std::string::npos);  // not measured, not stated
  s.set_elapsed(12.34);
  EXPECT_NE(s.text().find("\nelapsed     12.3 s (wall clock)\n"), std::string::npos) << s.text();
  s.set_elapsed(3725);
  EXPECT_NE(s.text().find("\nelapsed     3725.0 s (wall clock, 1h02m)\n"), std::string::npos) << s.text();
}

TEST(Compare, MannWhitneyTellsShiftedFromSameDistributions) {
  std::vector<double> x, y, z;
  for (int i = 0; i < 200; ++i) {
    x.push_back(std::sin(i * 1.7) * 100);
    y.push_back(std::sin(i * 2.3 + 1) * 100);   // same spread, other samples
    z.push_back(std::sin(i * 1.7) * 100 + 60);  // shifted
  }
  EXPECT_NEAR(mann_whitney_p(x, x), 1.0, 1e-12);
  EXPECT_GT(mann_whitney_p(x, y), 0.05);
  EXPECT_LT(mann_whitney_p(x, z), 1e-6);
  EXPECT_NEAR(mann_whitney_p(x, z), mann_whitney_p(z, x), 1e-12);
  EXPECT_TRUE(std::isnan(mann_whitney_p({}, x)));
}

TEST(BatchEvaluator, RefusesSpansOfDifferentSizesAndTuplesWithoutAnEnvironment) {
  EnvironmentCache cache;
  const SweepSpec s = parse_sweep_spec(small_spec, "spec.toml");
  std::vector<RunTuple> tuples{resolve_run(0, s.run(0), cache), resolve_run(1, s.run(1), cache)};
  std::vector<RunResult> one(1), two(2);
  const ThreadBatchEvaluator lanes(1);
  const SerialBatchEvaluator serial;
  for (const BatchEvaluator* e :
       {static_cast<const BatchEvaluator*>(&lanes), static_cast<const BatchEvaluator*>(&serial)}) {
    EXPECT_THROW(e->evaluate(tuples, one), std::invalid_argument);
    tuples[1].env.reset();
    EXPECT_THROW(e->evaluate(tuples, two), std::invalid_argument);
    tuples[1] = resolve_run(1, s.run(1), cache);
    EXPECT_EQ(e->evaluate(tuples, two), 2u);
  }
}

TEST(BatchEvaluator, EveryImplementationReportsProgressMarksFinishedSlotsAndStops) {
  EnvironmentCache cache;
  const SweepSpec s = parse_sweep_spec(small_spec, "spec.toml");
  std::vector<RunTuple> tuples;
  for (std::int64_t i = 0; i < s.size(); ++i) tuples.push_back(resolve_run(i, s.run(i), cache));
  const ThreadBatchEvaluator lanes(2);
  const SerialBatchEvaluator serial;
  for (const BatchEvaluator* e :
       {static_cast<const BatchEvaluator*>(&lanes), static_cast<const BatchEvaluator*>(&serial)}) {
    std::vector<RunResult> out(tuples.size());
    ProgressCounters counters;
    auto finished = std::make_unique<std::atomic<std::uint8_t>[]>(tuples.size());
    BatchObserver observer;
    observer.progress = &counters;
    observer.finished = finished.get();
    ASSERT_EQ(e->evaluate(tuples, out, observer), tuples.size());
    EXPECT_EQ(counters.done.load(), std::int64_t(tuples.size()));
    std::int64_t not_ok = 0;
    for (std::size_t i = 0; i < tuples.size(); ++i) {
      EXPECT_EQ(finished[i].load(), 1) << i;
      not_ok += out[i].status != Status::ok;
    }
    EXPECT_EQ(counters.failed.load(), not_ok);
    const std::atomic<bool> stop{true};
    BatchObserver stopped;
    stopped.stop = &stop;
    EXPECT_EQ(e->evaluate(tuples, out, stopped), 0u) << "runs started after the stop";
  }
}

// Threads claim runs a few at a time; stopped midway, the runs done are
// still exactly the returned prefix, each finished, and no other.
TEST(BatchEvaluator, AStopMidwayLeavesExactlyAPrefixFinished) {
  EnvironmentCache cache;
  const SweepSpec s = parse_sweep_spec(small_spec, "spec.toml");
  std::vector<RunTuple> tuples;
  for (int copy = 0; copy < 300; ++copy)
    for (std::int64_t i = 0; i < s.size(); ++i) tuples.push_back(resolve_run(i, s.run(i), cache));
  const ThreadBatchEvaluator lanes(2);
  for (const std::int64_t stop_after : {1, 40, 500}) {
    std::vector<RunResult> out(tuples.size());
    ProgressCounters counters;
    auto finished = std::make_unique<std::atomic<std::uint8_t>[]>(tuples.size());
    std::atomic<bool> stop{false};
    BatchObserver observer;
    observer.progress = &counters;
    observer.finished = finished.get();
    observer.stop = &stop;
    std::thread watcher([&] {
      while (counters.done.load() < stop_after && !stop.load()) std::this_thread::yield();
      stop.store(true);
    });
    const std::size_t done = lanes.evaluate(tuples, out, observer);
    stop.store(true);
    watcher.join();
    EXPECT_EQ(counters.done.load(), std::int64_t(done));
    for (std::size_t i = 0; i < tuples.size(); ++i) ASSERT_EQ(finished[i].load(), i < done ? 1 : 0) << i;
  }
}

// ------------------------------------------------------------------- store

TEST(H5Store, RoundTripsRowsAndProvenance) {
  TempDir tmp;
  const SweepSpec s = parse_sweep_spec(small_spec, "spec.toml");
  const auto rows = sweep_rows(s);
  const std::string path = tmp.file("sub/dir/r.h5");
  {
    H5RunWriter w(path);
    EXPECT_TRUE(std::filesystem::exists(path + ".partial"));
    EXPECT_FALSE(std::filesystem::exists(path));
    w.set_attribute("spec", s.text);
    w.append(std::vector<RunRow>(rows.begin(), rows.begin() + 5));
    w.append(std::vector<RunRow>(rows.begin() + 5, rows.end()));
    w.finish();
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  const auto ids = read_i64_column(path, "run_id");
  const auto ct = read_f64_column(path, "coverage_time");
  const auto status = read_text_column(path, "status");
  const auto boundary = read_text_column(path, "boundary");
  ASSERT_EQ(ids.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(ids[i], std::int64_t(i));
    EXPECT_EQ(status[i], to_string(rows[i].result.status));
    EXPECT_EQ(boundary[i], to_string(rows[i].tuple.params.boundary));
    if (rows[i].result.status == Status::ok) EXPECT_EQ(ct[i], rows[i].result.coverage_time);
    else EXPECT_TRUE(std::isnan(ct[i]));
  }
  EXPECT_EQ(read_attribute(path, "spec"), s.text);
}

TEST(H5Store, HasOneColumnPerParameterAndOutput) {
  for (const char* name : {"run_id", "env", "planner", "A", "B", "C", "f", "ds_index", "sr", "size_x", "start_x",
                           "status", "coverage_time", "final_coverage", "steps", "t_opt", "pr", "wall_time"})
    EXPECT_NE(find_column(name), nullptr) << name;
}

// -------------------------------------------------------------------- json

TEST(Json, WritesEveryColumnAndNanAsNull) {
  RunRow row;
  row.result.status = Status::timeout;
  const std::string j = row_to_json(row, false);
  for (const Column& c : result_columns()) EXPECT_NE(j.find("\"" + c.name + "\":"), std::string::npos) << c.name;
  EXPECT_NE(j.find("\"coverage_time\":null"), std::string::npos) << j;
  EXPECT_NE(j.find("\"status\":\"timeout\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"dt\":0.1,"), std::string::npos) << j;  // shortest round-trip text
  EXPECT_EQ(json_escape("a\"b\\c\n"), "a\\\"b\\\\c\\n");
}

TEST(AllPairsPlans, ParallelRowsEqualTheSerialPlansWhateverTheThreads) {
  using namespace bouncing_paper;
  Environment env;
  env.lx = env.ly = 4;
  env.obstacles = {{1, 1, 2, 3}};
  const CellGrid g = make_grid(env, 1.0, 8);
  const Roadmap rm = build_roadmap(g, {90.0, 225.0}, 1.0, 2.0);
  std::vector<int> sources;
  for (int c = 0; c < g.num_configs(); c += 3) sources.push_back(c);
  const auto one = all_pairs_plans(rm, sources, 1), two = all_pairs_plans(rm, sources, 2);
  ASSERT_EQ(one.size(), sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const PlanRow serial = all_plans_from(rm, sources[i]);
    EXPECT_EQ(one[i].plans, serial.plans) << i;
    EXPECT_EQ(two[i].plans, serial.plans) << i;
    EXPECT_EQ(two[i].weights, serial.weights) << i;
  }
}

TEST(SweepSpec, InputTheTomlParserCannotReadSafelyIsRefusedNamingTheLine) {
  // Found by tests/fuzz: toml++ 3.3.0 has undefined behaviour on these.
  for (const char* text : {"[[[1]]]", "[\x15", "a = 1\nb = 2 \xcc\x8e\n", "x = \"caf\xc3\xa9\"\n"}) {
    try {
      parse_sweep_spec(text, "bad.toml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const SpecError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.toml"), std::string::npos) << e.what();
    }
  }
  try {
    parse_sweep_spec("a = 1\nb = 2 \xcc\x8e\n", "bad.toml");
  } catch (const SpecError& e) {
    EXPECT_NE(std::string(e.what()).find("line 2: the character U+030E"), std::string::npos) << e.what();
  }
  // Other UTF-8 (an em dash) in strings and comments stays fine.
  EXPECT_NO_THROW(parse_sweep_spec("[sweep]\nname = \"a \xe2\x80\x94 b\" # \xe2\x80\x94\n", "ok.toml"));
}
