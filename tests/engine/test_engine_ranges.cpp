// Range values ({start, stop, step} and {start, stop, num}) are the doubles
// nearest the decimals a person means (engine/decimal_range.hpp), on small
// cases and on every range of every shipped spec.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/spec/decimal_range.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "engine/spec/toml.hpp"
#include "kernels/core/param_table.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;

namespace {

// Decimal places of v's shortest round-trip form (0.35 -> 2, 1e-06 -> 6, 800 -> 0).
int decimals_of(double v) {
  char buf[40];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  const std::string s(buf, res.ptr);
  const std::size_t dot = s.find('.'), e = s.find('e');
  const int fraction = dot == std::string::npos ? 0 : int(e - dot - 1);
  return std::max(0, fraction - std::stoi(s.substr(e + 1)));
}

double read(const std::string& text) {
  double v = 0;
  std::from_chars(text.data(), text.data() + text.size(), v);
  return v;
}

// True when v is the double nearest the exact value x, decided in long
// double (x itself computed from exact integers, so off by far less than
// the gap to v's neighbours).
bool nearest_to(double v, long double x) {
  const long double d = std::fabs(static_cast<long double>(v) - x);
  return d <= std::fabs(static_cast<long double>(std::nextafter(v, INFINITY)) - x) &&
         d <= std::fabs(static_cast<long double>(std::nextafter(v, -INFINITY)) - x);
}

// 10^p as a long double (exact for p <= 27).
long double pow10_ld(int p) {
  long double r = 1;
  for (int i = 0; i < p; ++i) r *= 10;
  return r;
}

std::vector<double> floating_step_values(double start, double stop, double step) {
  std::vector<double> out;
  const double n = std::floor((stop - start) / step + 1e-9) + 1;
  for (int i = 0; i < int(n); ++i) out.push_back(start + double(i) * step);
  return out;
}

// Checks a {start, stop, step} range's values: as many as the floating-point
// formula gives, each within 1e-9 of a step of start + k step, and each with
// no more decimal places than start and step have: so each is the double of
// the decimal start + k step itself (the one such decimal that near).
void expect_decimal_step_range(double start, double stop, double step, const std::string& where) {
  const std::vector<double> got = DecimalRange::by_step(start, stop, step).values();
  const std::vector<double> naive = floating_step_values(start, stop, step);
  ASSERT_EQ(got.size(), naive.size()) << where;
  const int places = std::max(decimals_of(start), decimals_of(step));
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_NEAR(got[k], naive[k], 1e-9 * std::fabs(step)) << where << "[" << k << "]";
    EXPECT_LE(decimals_of(got[k]), places) << where << "[" << k << "] = " << format_number(got[k]);
  }
}

// Checks a {start, stop, num} range: the ends exact, each interior value the
// double nearest start + (stop - start) i / (num - 1) computed exactly.
void expect_decimal_count_range(double start, double stop, std::int64_t num, const std::string& where) {
  const std::vector<double> got = DecimalRange::by_count(start, stop, num).values();
  ASSERT_EQ(got.size(), std::size_t(num)) << where;
  EXPECT_EQ(got.front(), start) << where;
  EXPECT_EQ(got.back(), stop) << where;
  const int p = std::max(decimals_of(start), decimals_of(stop));
  ASSERT_LE(p, 12) << where << ": the check below needs the scaled integers exact in a long double";
  const long double s = std::round(static_cast<long double>(start) * pow10_ld(p)),
                    t = std::round(static_cast<long double>(stop) * pow10_ld(p));
  for (std::int64_t i = 1; i + 1 < num; ++i) {
    const long double x = (s * (num - 1) + (t - s) * i) / ((num - 1) * pow10_ld(p));
    EXPECT_TRUE(nearest_to(got[std::size_t(i)], x))
        << where << "[" << i << "] = " << format_number(got[std::size_t(i)]);
  }
}

}  // namespace

TEST(DecimalRange, StepRangesGiveTheDecimalsAPersonWrites) {
  EXPECT_EQ(DecimalRange::by_step(0.2, 0.4, 0.05).values(), (std::vector<double>{0.2, 0.25, 0.3, 0.35, 0.4}));
  EXPECT_EQ(DecimalRange::by_step(0, 1, 0.1).values(),
            (std::vector<double>{0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1}));
  // The floating-point formula gives 0.30000000000000004 and 0.35000000000000003 here.
  ASSERT_NE(0.2 + 2 * 0.05, 0.3);
  ASSERT_NE(0.2 + 3 * 0.05, 0.35);
  // Fig. 6's grid: every value is the decimal 0.35 + k / 100.
  const std::vector<double> a = DecimalRange::by_step(0.35, 0.65, 0.01).values();
  ASSERT_EQ(a.size(), 31u);
  for (int k = 0; k < 31; ++k) EXPECT_EQ(a[std::size_t(k)], read("0." + std::to_string(35 + k))) << k;
  // Downwards, a stop off the grid, integers, a step finer than start.
  EXPECT_EQ(DecimalRange::by_step(1, 0, -0.25).values(), (std::vector<double>{1, 0.75, 0.5, 0.25, 0}));
  EXPECT_EQ(DecimalRange::by_step(0, 1, 0.3).values(), (std::vector<double>{0, 0.3, 0.6, 0.9}));
  EXPECT_EQ(DecimalRange::by_step(800, 1900, 100).values().size(), 12u);
  EXPECT_EQ(DecimalRange::by_step(-1.5, -1.2, 0.001).values().size(), 301u);
  EXPECT_EQ(DecimalRange::by_step(-1.5, -1.2, 0.001).at(123), -1.377);
  EXPECT_EQ(DecimalRange::by_step(1e6, 1e6 + 1, 0.125).values().back(), 1e6 + 1);
  EXPECT_TRUE(DecimalRange::by_step(0.2, 0.4, 0.05).exact());
}

TEST(DecimalRange, CountRangesKeepTheirEndsAndAreAsExactAsADoubleCanBe) {
  EXPECT_EQ(DecimalRange::by_count(0.35, 0.65, 7).values(),
            (std::vector<double>{0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65}));
  EXPECT_EQ(DecimalRange::by_count(0.1, 0.8, 8).values(),
            (std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8}));
  EXPECT_EQ(DecimalRange::by_count(0, 1, 5).values(), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  EXPECT_EQ(DecimalRange::by_count(2, 2, 1).values(), (std::vector<double>{2}));
  // 0.9 / 31 does not terminate: the double nearest each exact value
  // (checked against Python's fractions: float(Fraction('0.051') + Fraction('0.9') * i / 31)).
  const std::vector<double> x = DecimalRange::by_count(0.051, 0.951, 32).values();
  EXPECT_EQ(x[1], 0.08003225806451612);
  EXPECT_EQ(x[7], 0.2542258064516129);
  EXPECT_EQ(x[8], 0.28325806451612906);
  EXPECT_EQ(x[30], 0.9219677419354839);
  expect_decimal_count_range(0.051, 0.951, 32, "0.051..0.951 num 32");
  expect_decimal_count_range(-3, 7.5, 1000, "-3..7.5 num 1000");
  expect_decimal_count_range(1e-3, 2e-3, 3, "1e-3..2e-3 num 3");
}

TEST(DecimalRange, NumbersPastScaledIntegersFallBackToTheFloatingFormula) {
  const DecimalRange tiny = DecimalRange::by_step(1e-300, 5e-300, 1e-300);
  EXPECT_FALSE(tiny.exact());
  EXPECT_EQ(tiny.values().size(), 5u);
  const DecimalRange wide = DecimalRange::by_count(1e-20, 1e20, 3);
  EXPECT_FALSE(wide.exact());
  EXPECT_EQ(wide.values(), (std::vector<double>{1e-20, 1e-20 + (1e20 - 1e-20) / 2, 1e20}));
  // A step finer than a range's span allows, within the limits, is exact.
  EXPECT_TRUE(DecimalRange::by_step(0, 1e8, 1e-8).exact());
  EXPECT_EQ(DecimalRange::by_step(0, 1e8, 1e-8).at(30000000), 0.3);
}

TEST(SweepSpec, RangeAxesHoldTheDecimalsNotTheirFloatNoise) {
  const SweepSpec s = parse_sweep_spec("[axes]\nC = { start = 0.2, stop = 0.4, step = 0.05 }\n", "x");
  ASSERT_EQ(s.axes[0].values.size(), 5u);
  EXPECT_EQ(s.run(2).params.C, 0.3);
  EXPECT_EQ(s.run(3).params.C, 0.35);
  EXPECT_EQ(format_number(s.run(3).params.C), "0.35");
}

// Every range in experiments/*.toml: its values are the decimals (step), or
// the nearest doubles (num), and the spec's expansion holds exactly them.
TEST(SweepSpec, EveryRangeOfEveryShippedSpecIsDecimalExact) {
  namespace fs = std::filesystem;
  int ranges = 0, specs = 0;
  for (const auto& entry : fs::directory_iterator(std::string(CHAOSWEEP_SOURCE_DIR) + "/experiments")) {
    if (entry.path().extension() != ".toml") continue;
    const std::string path = entry.path().string();
    ++specs;
    const SweepSpec spec = load_sweep_spec(path);
    std::vector<const Axis*> axes;
    for (const Axis& a : spec.axes) axes.push_back(&a);
    for (const SpecPart& p : spec.parts)
      for (const Axis& a : p.axes) axes.push_back(&a);
    // A key's values along an axis that sets it (empty when it does not).
    auto column = [](const Axis& a, const std::string& key) {
      std::vector<double> out;
      if (a.sampler) return out;
      for (const Settings& s : a.values)
        for (const auto& [k, v] : s)
          if (k == key) out.push_back(std::get<double>(v));
      return out;
    };
    // Walk every table of the file; a range is a table of start, stop and step or num.
    std::function<void(const toml::table&, const std::string&)> walk = [&](const toml::table& t,
                                                                           const std::string& at) {
      for (auto&& [k, node] : t) {
        const std::string key(k.str()), where = path + ": " + at + key;
        if (const toml::array* arr = node.as_array()) {
          for (std::size_t i = 0; i < arr->size(); ++i)
            if (const toml::table* sub = arr->get(i)->as_table()) walk(*sub, at + key + "[" + std::to_string(i) + "].");
          continue;
        }
        const toml::table* r = node.as_table();
        if (!r) continue;
        if (!(r->contains("start") && r->contains("stop") && (r->contains("step") || r->contains("num")))) {
          walk(*r, at + key + ".");
          continue;
        }
        ++ranges;
        const double start = *(*r)["start"].value<double>(), stop = *(*r)["stop"].value<double>();
        std::vector<double> want;
        if (r->contains("step")) {
          const double step = *(*r)["step"].value<double>();
          expect_decimal_step_range(start, stop, step, where);
          want = DecimalRange::by_step(start, stop, step).values();
        } else {
          const auto num = *(*r)["num"].value<std::int64_t>();
          expect_decimal_count_range(start, stop, num, where);
          want = DecimalRange::by_count(start, stop, num).values();
        }
        bool expanded = false;
        for (const Axis* a : axes) expanded = expanded || column(*a, key) == want;
        EXPECT_TRUE(expanded) << where << ": no axis of the loaded spec holds these values";
      }
    };
    walk(toml::parse_file(path), "");
  }
  EXPECT_GE(specs, 10);
  EXPECT_GE(ranges, 20);  // the shipped specs hold 25 ranges today
}
