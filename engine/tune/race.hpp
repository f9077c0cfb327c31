#pragma once
// One case's iterated race (irace's algorithm; Lopez-Ibanez et al., "The
// irace package", Operations Research Perspectives 3, 2016): configurations
// sampled over the domain race on seeds 0, 1, ... (every configuration of a
// race on the same seeds, so the test is blocked on the seed); those a test
// shows worse are dropped; the best survivors are the elites, and new
// configurations are sampled around them (reals: a normal whose spread
// shrinks each iteration, a draw beyond the range landing on its end, as the
// first sample holds the ends too; choices: probabilities moved towards the
// elite's value) for the next race, until the iterations' share of the
// budget is spent; the rest (post_selection) races the last elites alone on
// further seeds, and the survivor is the choice.
// A step machine: next() says what to run, take() gets the costs back, so the
// caller can batch many cases' evaluations, and the race depends on the
// costs alone (not on how, or on how many threads, they were run).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/tune/tune_spec.hpp"

namespace chaosweep {

struct Candidate {
  std::int64_t id = 0;         // 1, 2, ... in order of creation
  std::vector<double> values;  // per parameter: the real value, or the index of the choice
  // Per parameter, for choices: the distribution its children are drawn from.
  std::vector<std::vector<double>> probabilities;
  int born = 0;               // the iteration that sampled it
  std::vector<double> costs;  // by seed; NaN: not run (+inf: missed the target)
  bool alive = false;         // racing now, or an elite between races
};

struct RaceEvaluation {
  std::int64_t config = 0;
  std::int64_t seed = 0;
  int round = 0;  // the iteration
};

class Race {
 public:
  // `parameters`: the case's own, in order; `settings` gives the test, its
  // confidence, first_test, each_test and digits; `seed` the tuner's draws.
  Race(std::vector<TuneParameter> parameters, std::int64_t budget, const TuneSpec& settings, std::uint64_t seed);

  // The evaluations to run next (none: the race is over).
  std::vector<RaceEvaluation> next();
  // The costs of next()'s evaluations, in its order.
  void take(std::span<const double> costs);

  bool done() const { return done_; }
  std::int64_t spent() const { return spent_; }
  int iteration() const { return iteration_; }
  // The first elite (the best of the last race); 0 before any race ended.
  std::int64_t best() const { return elites_.empty() ? 0 : elites_.front(); }
  const std::vector<std::int64_t>& elites() const { return elites_; }
  const Candidate& candidate(std::int64_t id) const { return pool_[std::size_t(id - 1)]; }
  const std::vector<Candidate>& candidates() const { return pool_; }
  const std::vector<TuneParameter>& parameters() const { return parameters_; }

 private:
  void start_iteration();
  void start_post_selection();
  void begin_race();  // from seed 0, on iteration_budget_
  void end_iteration();
  void eliminate();
  std::vector<std::int64_t> alive() const;
  // Seeds 0 .. seeds_-1 (rows) by `ids` (columns): the blocked tests' input.
  std::vector<double> costs_by_seed(const std::vector<std::int64_t>& ids) const;
  // Alive configurations ranked on the seeds all of them ran (best first).
  std::vector<std::int64_t> ranked(const std::vector<std::int64_t>& ids) const;
  void add_initial(int n);
  void add_children(int n);
  bool add(Candidate c);  // false for a duplicate of a known configuration
  double rounded(double v, const TuneParameter& p) const;
  double uniform();
  double normal();

  std::vector<TuneParameter> parameters_;
  std::int64_t budget_;
  TuneSpec settings_;
  std::uint64_t rng_;
  int n_iterations_, n_survivors_;
  std::vector<Candidate> pool_;
  std::vector<std::int64_t> elites_;
  int iteration_ = 0;
  bool racing_ = false, done_ = false;
  std::int64_t spent_ = 0, iteration_budget_ = 0, iteration_spent_ = 0;
  std::int64_t seeds_ = 0;  // seeds 0 .. seeds_-1 done by every alive configuration
  std::vector<RaceEvaluation> pending_;
  std::int64_t pending_seeds_ = 0;
  int new_this_iteration_ = 0;
  bool exhausted_ = false;
  bool post_selection_ = false;  // the elites' last race, on the budget kept back
  std::int64_t race_budget_ =
      0;  // the iterations' share of the budget  // the first iteration took every point of a finite domain
};

}  // namespace chaosweep
