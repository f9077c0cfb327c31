#pragma once
// Runs a tune (engine/tune/tune_spec.hpp) on a batch evaluator: every case's
// race (engine/tune/race.hpp) in step, the evaluations of all cases of a
// step in one batch, then the validation runs. Cases race independently, so
// a shard of the cases (K of N: the cases i with i % N == K) gives the rows
// the whole tune gives for them: a case's k-th run has run_id
// tune_run_id(cases, i, k), whatever else runs beside it. Rows reach the sink
// in the order the steps ask for them. Resuming replays the tune from the
// rows already stored (their costs), running only what they lack.
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
  std::int64_t run_id = 0, param_hash = 0;
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
  int shard_index = 0, shard_count = 1;  // the cases raced: i % shard_count == shard_index
};

struct TuneOutcome {
  std::vector<std::size_t> cases;          // the cases raced and validated (the shard's)
  std::vector<std::optional<Race>> races;  // per case (none: a case without parameters, or not raced)
  // Per case: the configuration validated as the tuner's choice (0: none).
  std::vector<std::int64_t> chosen;
  std::int64_t runs = 0;  // rows in the file after this session
  bool stopped = false;   // by opt.stop: the rows handed over are a prefix
};

using TuneSink = std::function<void(const std::vector<RunRow>&)>;

// Runs the tune; `known` are the rows already stored (in the order the sink
// had them), whose run_ids and tuples must be the ones the tune makes (else
// std::runtime_error naming the first that differs). Calls `sink` with the
// rows after them, a step at a time.
TuneOutcome run_tune(const TuneSpec& tune, const BatchEvaluator& evaluator, const TuneOptions& opt,
                     const TuneSink& sink, EnvironmentCache& cache, const std::vector<KnownRun>& known = {});

// The race's own seed of case `index` (independent races, whatever else is in the spec).
std::uint64_t race_seed(const TuneSpec& tune, std::size_t index);

// The run_id of the k-th run (from 0, race then validation) of case `index`
// of a tune of `cases` cases: it depends on the case alone, so the rows of a
// tune's shards merge into those of the whole tune.
inline std::int64_t tune_run_id(std::size_t cases, std::size_t index, std::int64_t k) {
  return std::int64_t(index) + std::int64_t(cases) * k;
}

// Whether case `index` is in shard `shard_index` of `shard_count`.
inline bool tune_case_in_shard(std::size_t index, int shard_index, int shard_count) {
  return int(index % std::size_t(shard_count)) == shard_index;
}

// The most rows shard `shard_index` of `shard_count` of the tune can write:
// its cases' budgets and validation runs (twice those beside a grid's best).
std::int64_t tune_most_rows(const TuneSpec& tune, bool grid, int shard_index = 0, int shard_count = 1);

}  // namespace chaosweep
