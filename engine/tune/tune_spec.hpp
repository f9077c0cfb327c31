#pragma once
// The [tune] section of a spec (docs/tune.md): what `chaosweep tune` races in
// each case. The spec's runs are the cases (a Table 1 row: map, SR,
// environment, technique set); [tune] names the parameters to search and
// their domains, which parts search which, the elimination test, the budget,
// and the seeds of the validation runs.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

// One searched parameter: a continuous range, or a list of values.
struct TuneParameter {
  std::string key;                 // a run parameter (apply_setting's keys)
  bool real = false;               // a {min, max} range, values rounded to TuneSpec::digits ...
  double lo = 0, hi = 0;           //
  std::vector<SpecValue> choices;  // ... or these values (categorical)
};

enum class RaceTest { friedman, wilcoxon };
const char* to_string(RaceTest t);

struct TuneCase {
  RunSpec run;                          // the spec's run: its label names the case
  std::vector<std::size_t> parameters;  // indices into TuneSpec::parameters (none: only validated)
  std::int64_t budget = 0;              // race runs this case may spend (validation not counted)
  std::string part;                     // its part ("" for a spec without parts)
};

struct TuneSpec {
  std::vector<TuneParameter> parameters;
  std::vector<TuneCase> cases;
  std::uint64_t seed = 0;  // the tuner's own draws
  double confidence = 0.95;
  RaceTest test = RaceTest::friedman;
  int first_test = 5;           // seeds every configuration runs before its first test
  int each_test = 1;            // seeds between tests
  int digits = 4;               // significant digits of a sampled real value
  double post_selection = 0.2;  // share of a case's budget kept to race its last elites on more seeds
  int validation_seeds = 32;
  std::int64_t validation_first_seed = 1000000;  // far from the race's seeds 0, 1, ...
};

// The tune of `spec` (whose `tune` holds the [tune] table); `budget`
// replaces every case's budget (--budget). Throws SpecError naming the key
// (tune.parameters.c, tune.part.MZ.budget, ...) and what it may be.
TuneSpec tune_spec_of(const SweepSpec& spec, const std::string& source_name,
                      std::optional<std::int64_t> budget = std::nullopt);

// The run of case `c` with configuration `values` (one per parameter of the
// case: a real value, or an index into the choices) on seed `seed`.
RunSpec tune_run(const TuneSpec& tune, const TuneCase& c, const std::vector<double>& values, std::int64_t seed);

// The smallest budget a case with parameters needs: first_test seeds of two
// configurations.
std::int64_t minimum_budget(const TuneSpec& tune);

}  // namespace chaosweep
