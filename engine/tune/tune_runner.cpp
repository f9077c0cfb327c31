#include "engine/tune/tune_runner.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include "engine/rows/run_hash.hpp"
#include "engine/spec/run_tuple.hpp"
#include "kernels/math/splitmix.hpp"

namespace chaosweep {

namespace {

struct Wanted {
  std::size_t case_index = 0;
  std::int64_t config = 0;
  std::int64_t seed = 0;
  int round = 0;
  const std::vector<double>* values = nullptr;
};

// Runs `wanted` as run_ids next, next + 1, ...: those already stored give
// their cost; the rest run in one batch and go to the sink. False when
// stopped before all of them ran.
class StepRunner {
 public:
  StepRunner(const TuneSpec& tune, const BatchEvaluator& evaluator, const TuneOptions& opt, const TuneSink& sink,
             EnvironmentCache& cache, const std::vector<KnownRun>& known)
      : tune_(tune),
        evaluator_(evaluator),
        opt_(opt),
        sink_(sink),
        cache_(cache),
        known_(known),
        case_runs_(tune.cases.size(), 0) {}

  bool run(const std::vector<Wanted>& wanted, std::vector<double>& costs) {
    costs.assign(wanted.size(), 0.0);
    std::vector<RunTuple> fresh;
    std::vector<std::size_t> slot;
    for (std::size_t k = 0; k < wanted.size(); ++k) {
      const Wanted& w = wanted[k];
      const TuneCase& c = tune_.cases[w.case_index];
      const std::int64_t run_id = tune_run_id(tune_.cases.size(), w.case_index, case_runs_[w.case_index]++);
      RunTuple t = resolve_run(run_id, tune_run(tune_, c, *w.values, w.seed), cache_);
      t.race_round = w.round;
      t.config_id = w.config;
      if (next_ < std::int64_t(known_.size())) {
        const KnownRun& kr = known_[std::size_t(next_)];
        if (kr.run_id != run_id || kr.param_hash != param_hash(t.params, t.env_spec))
          throw std::runtime_error("row " + std::to_string(next_) + " is stored as run_id " +
                                   std::to_string(kr.run_id) + ", not as this tune makes it (run_id " +
                                   std::to_string(run_id) + (kr.run_id == run_id ? ", param_hash differs" : "") +
                                   "): the file was written by another spec, shard or engine");
        costs[k] = kr.cost;
      } else {
        fresh.push_back(std::move(t));
        slot.push_back(k);
      }
      ++next_;
    }
    if (fresh.empty()) return true;
    std::vector<RunResult> results(fresh.size());
    BatchObserver observer;
    observer.stop = opt_.stop;
    observer.progress = opt_.progress;
    const std::size_t done = evaluator_.evaluate(fresh, results, observer);
    std::vector<RunRow> rows;
    rows.reserve(done);
    for (std::size_t k = 0; k < done; ++k) {
      costs[slot[k]] = tune_cost(results[k]);
      rows.push_back({std::move(fresh[k]), std::move(results[k])});
    }
    if (!rows.empty()) sink_(rows);
    stored_ += std::int64_t(done);
    return done == fresh.size();
  }

  std::int64_t rows() const { return std::int64_t(known_.size()) + stored_; }

 private:
  const TuneSpec& tune_;
  const BatchEvaluator& evaluator_;
  const TuneOptions& opt_;
  const TuneSink& sink_;
  EnvironmentCache& cache_;
  const std::vector<KnownRun>& known_;
  std::vector<std::int64_t> case_runs_;  // runs asked of each case so far
  std::int64_t next_ = 0, stored_ = 0;   // rows asked for so far (stored or run), rows run
};

}  // namespace

double tune_cost(const RunResult& r) {
  return r.status == Status::ok ? r.coverage_time : std::numeric_limits<double>::infinity();
}

std::uint64_t race_seed(const TuneSpec& tune, std::size_t index) {
  std::uint64_t s = tune.seed + 0x9e3779b97f4a7c15ULL * (std::uint64_t(index) + 1);
  return splitmix64(s);
}

std::int64_t tune_most_rows(const TuneSpec& tune, bool grid, int shard_index, int shard_count) {
  std::int64_t n = 0;
  for (std::size_t i = 0; i < tune.cases.size(); ++i)
    if (tune_case_in_shard(i, shard_index, shard_count))
      n += tune.cases[i].budget + std::int64_t(tune.validation_seeds) * (grid ? 2 : 1);
  return n;
}

TuneOutcome run_tune(const TuneSpec& tune, const BatchEvaluator& evaluator, const TuneOptions& opt,
                     const TuneSink& sink, EnvironmentCache& cache, const std::vector<KnownRun>& known) {
  TuneOutcome out;
  const std::size_t n = tune.cases.size();
  out.races.resize(n);
  out.chosen.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (tune_case_in_shard(i, opt.shard_index, opt.shard_count)) out.cases.push_back(i);
  for (std::size_t i : out.cases) {
    const TuneCase& c = tune.cases[i];
    if (c.parameters.empty()) continue;
    std::vector<TuneParameter> own;
    for (std::size_t j : c.parameters) own.push_back(tune.parameters[j]);
    out.races[i].emplace(std::move(own), c.budget, tune, race_seed(tune, i));
  }
  StepRunner step(tune, evaluator, opt, sink, cache, known);
  std::vector<double> costs;
  // The races, in step: each asks for its next evaluations; all run at once.
  for (;;) {
    std::vector<Wanted> wanted;
    std::vector<std::size_t> first(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      first[i] = wanted.size();
      if (!out.races[i] || out.races[i]->done()) continue;
      for (const RaceEvaluation& e : out.races[i]->next())
        wanted.push_back({i, e.config, e.seed, e.round, &out.races[i]->candidate(e.config).values});
    }
    first[n] = wanted.size();
    if (wanted.empty()) break;
    if (!step.run(wanted, costs)) {
      out.stopped = true;
      out.runs = step.rows();
      return out;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (first[i + 1] > first[i])
        out.races[i]->take(std::span<const double>(costs.data() + first[i], first[i + 1] - first[i]));
  }
  // Validation on seeds the races never used: the tuner's choice (a case
  // without parameters: its one configuration, id 1) and any given beside it.
  static const std::vector<double> none;
  std::vector<Wanted> wanted;
  for (std::size_t i : out.cases) {
    const std::vector<double>* values = &none;
    out.chosen[i] = 1;
    if (out.races[i]) {
      out.chosen[i] = out.races[i]->best();
      if (out.chosen[i] == 0) continue;
      values = &out.races[i]->candidate(out.chosen[i]).values;
    }
    const bool beside = i < opt.also_validate.size() && opt.also_validate[i];
    for (int k = 0; k < tune.validation_seeds; ++k) {
      const std::int64_t seed = tune.validation_first_seed + k;
      wanted.push_back({i, out.chosen[i], seed, 0, values});
      if (beside) wanted.push_back({i, 0, seed, 0, &*opt.also_validate[i]});
    }
  }
  if (!wanted.empty() && !step.run(wanted, costs)) out.stopped = true;
  out.runs = step.rows();
  return out;
}

}  // namespace chaosweep
