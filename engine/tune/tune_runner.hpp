#pragma once
// Runs a tune (engine/tune/tune_spec.hpp) on a batch evaluator: every case's
// race (engine/tune/race.hpp) in step, the evaluations of all cases of a
// step in one batch, then the validation runs. Run ids follow the order in
// which the steps ask for runs, so they depend on the spec alone; rows reach
// the sink in run_id order. Resuming replays the tune from the rows already
// stored (their costs), running only what they lack.
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "engine/run/batch_evaluator.hpp"
#include "engine/spec/environment_loader.hpp"
#include "engine/tune/race.hpp"

namespace chaosweep {

// A stored row, as the replay needs it.
struct KnownRun {
  std::int64_t param_hash = 0;
  double cost = 0;  // coverage_time of an ok run, else +inf
};

// The tuner's cost of a run: its coverage time, or +inf when it missed the
// target (any status but ok), so that it ranks after every run that made it.
double tune_cost(const RunResult& r);

struct TuneOptions {
  const std::atomic<bool>* stop = nullptr;  // set: runs in flight finish, the tune returns
  ProgressCounters* progress = nullptr;
  // Per case: a configuration validated beside the tuner's (config_id 0),
  // e.g. a grid search's best, as values of the case's parameters.
  std::vector<std::optional<std::vector<double>>> also_validate;
};

struct TuneOutcome {
  std::vector<std::optional<Race>> races;  // per case (none: a case without parameters)
  // Per case: the configuration validated as the tuner's choice (0: none).
  std::vector<std::int64_t> chosen;
  std::int64_t runs = 0;  // rows in the file after this session
  bool stopped = false;   // by opt.stop: the rows handed over are a prefix
};

using TuneSink = std::function<void(const std::vector<RunRow>&)>;

// Runs the tune; `known` are the rows of run_ids 0.. already stored, whose
// tuples must be the ones the tune makes (else std::runtime_error naming the
// first that differs). Calls `sink` with the rows after them, a step at a
// time, in run_id order.
TuneOutcome run_tune(const TuneSpec& tune, const BatchEvaluator& evaluator, const TuneOptions& opt,
                     const TuneSink& sink, EnvironmentCache& cache, const std::vector<KnownRun>& known = {});

// The race's own seed of case `index` (independent races, whatever else is in the spec).
std::uint64_t race_seed(const TuneSpec& tune, std::size_t index);

}  // namespace chaosweep
