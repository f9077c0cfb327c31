#include "engine/tune/race.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "engine/tune/race_stats.hpp"
#include "kernels/math/splitmix.hpp"

namespace chaosweep {

namespace {

// irace's defaults: floor(2 + log2(parameters)) iterations and survivors.
int log_count(std::size_t parameters) {
  return int(std::floor(2.0 + std::log2(double(std::max<std::size_t>(parameters, 1)))));
}

}  // namespace

Race::Race(std::vector<TuneParameter> parameters, std::int64_t budget, const TuneSpec& settings, std::uint64_t seed)
    : parameters_(std::move(parameters)),
      budget_(budget),
      settings_(settings),
      rng_(seed),
      n_iterations_(log_count(parameters_.size())),
      n_survivors_(log_count(parameters_.size())) {
  settings_.cases.clear();  // only the race's settings are kept
  race_budget_ = budget_ - std::int64_t(std::floor(double(budget_) * settings_.post_selection));
  if (parameters_.empty() || budget_ <= 0) done_ = true;
}

double Race::uniform() { return uniform01(rng_); }

double Race::normal() {
  // Box-Muller from two draws of (0, 1]: the same numbers on every machine.
  const double u = 1.0 - uniform(), v = uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * 3.141592653589793 * v);
}

// A sampled real, at settings.digits significant digits: a value the printed
// configuration states exactly, inside the range.
double Race::rounded(double v, const TuneParameter& p) const {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", settings_.digits, v);
  return std::clamp(std::strtod(buf, nullptr), p.lo, p.hi);
}

bool Race::add(Candidate c) {
  for (const Candidate& o : pool_)
    if (o.values == c.values) return false;
  c.id = std::int64_t(pool_.size()) + 1;
  c.born = iteration_;
  c.alive = true;
  pool_.push_back(std::move(c));
  return true;
}

// A Latin hypercube over the domain (a choice is its stratum's share of the
// list); for a domain of choices alone that has at most n points, every point.
void Race::add_initial(int n) {
  const std::size_t d = parameters_.size();
  std::vector<std::vector<double>> uniform_probabilities(d);
  double points = 1;
  bool all_choices = true;
  for (std::size_t i = 0; i < d; ++i) {
    const TuneParameter& p = parameters_[i];
    if (p.real) {
      all_choices = false;
    } else {
      points *= double(p.choices.size());
      uniform_probabilities[i].assign(p.choices.size(), 1.0 / double(p.choices.size()));
    }
  }
  if (all_choices && points <= double(n)) {
    exhausted_ = true;
    for (std::int64_t k = 0; k < std::int64_t(points); ++k) {
      Candidate c;
      c.probabilities = uniform_probabilities;
      std::int64_t rest = k;
      for (std::size_t i = d; i-- > 0;) {
        const auto m = std::int64_t(parameters_[i].choices.size());
        c.values.insert(c.values.begin(), double(rest % m));
        rest /= m;
      }
      add(std::move(c));
    }
    return;
  }
  std::vector<std::vector<int>> strata(d);
  for (auto& s : strata) {
    s.resize(std::size_t(n));
    std::iota(s.begin(), s.end(), 0);
    for (std::size_t k = s.size(); k > 1; --k) std::swap(s[k - 1], s[std::size_t(uniform() * double(k))]);
  }
  for (int k = 0; k < n; ++k) {
    Candidate c;
    c.probabilities = uniform_probabilities;
    for (std::size_t i = 0; i < d; ++i) {
      const TuneParameter& p = parameters_[i];
      // A real's outermost strata sample its range's ends themselves: CT
      // often falls all the way to an end (c = 1 or f = 6 on several Table 1
      // maps), and no draw inside a stratum reaches it. (With two samples
      // or fewer every sample would be an end: those stay drawn.)
      const int stratum = strata[i][std::size_t(k)];
      double u = (stratum + uniform()) / double(n);
      if (p.real && n > 2 && (stratum == 0 || stratum == n - 1)) u = stratum == 0 ? 0.0 : 1.0;
      c.values.push_back(p.real ? rounded(p.lo + u * (p.hi - p.lo), p)
                                : std::min(double(p.choices.size() - 1), std::floor(u * double(p.choices.size()))));
    }
    add(std::move(c));
  }
}

// Children of the elites: the parent drawn with weight (elites - rank + 1);
// a real from a normal around the parent's value, its spread (range / 2)
// shrinking by (1/N_1)^(1/parameters) per iteration, and a draw beyond the
// range put on the range's end (irace draws again instead, so an optimum at
// an end is only ever approached: see add_initial);
// a choice from the parent's probabilities moved towards its own value.
void Race::add_children(int n) {
  const std::size_t e = elites_.size();
  const double weight_total = double(e * (e + 1)) / 2.0;
  // (1/N_1)^((j-1)/P), N_1 the first iteration's sample: the spread shrinks
  // every iteration, however few configurations a late one adds.
  int first = 0;
  for (const Candidate& c : pool_) first += c.born == 1;
  const double shrink = std::pow(1.0 / double(std::max(first, 2)), double(iteration_ - 1) / double(parameters_.size()));
  const double towards = std::min(0.9, double(iteration_ - 1) / double(n_iterations_));
  for (int made = 0, tries = 0; made < n && tries < 50 * n; ++tries) {
    double w = uniform() * weight_total;
    std::size_t r = 0;
    while (r + 1 < e && (w -= double(e - r)) >= 0) ++r;
    const Candidate& parent = candidate(elites_[r]);
    Candidate c;
    c.probabilities = parent.probabilities;
    for (std::size_t i = 0; i < parameters_.size(); ++i) {
      const TuneParameter& p = parameters_[i];
      if (p.real) {
        const double sd = (p.hi - p.lo) / 2.0 * shrink;
        c.values.push_back(rounded(std::clamp(parent.values[i] + sd * normal(), p.lo, p.hi), p));
      } else {
        std::vector<double>& q = c.probabilities[i];
        for (double& x : q) x *= 1.0 - towards;
        q[std::size_t(parent.values[i])] += towards;
        double u = uniform();
        std::size_t pick = 0;
        while (pick + 1 < q.size() && (u -= q[pick]) >= 0) ++pick;
        c.values.push_back(double(pick));
      }
    }
    if (add(std::move(c))) ++made;
  }
}

std::vector<std::int64_t> Race::alive() const {
  std::vector<std::int64_t> ids;
  for (const Candidate& c : pool_)
    if (c.alive) ids.push_back(c.id);
  return ids;
}

std::vector<double> Race::costs_by_seed(const std::vector<std::int64_t>& ids) const {
  std::vector<double> m;
  m.reserve(std::size_t(seeds_) * ids.size());
  for (std::int64_t s = 0; s < seeds_; ++s)
    for (std::int64_t id : ids) m.push_back(candidate(id).costs[std::size_t(s)]);
  return m;
}

std::vector<std::int64_t> Race::ranked(const std::vector<std::int64_t>& ids) const {
  std::vector<double> sums(ids.size(), 0.0);
  if (seeds_ > 0 && ids.size() > 1) {
    sums = friedman(costs_by_seed(ids), std::size_t(seeds_), ids.size()).rank_sums;
  }
  std::vector<std::size_t> order(ids.size());
  std::iota(order.begin(), order.end(), 0);
  // Ties: the older configuration first (it has run more seeds).
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return sums[a] < sums[b]; });
  std::vector<std::int64_t> out;
  for (std::size_t k : order) out.push_back(ids[k]);
  return out;
}

void Race::start_iteration() {
  ++iteration_;
  const std::int64_t remaining = race_budget_ - spent_;
  iteration_budget_ = remaining / std::max(1, n_iterations_ - iteration_ + 1);
  const std::int64_t per = settings_.first_test + std::min(5, iteration_);
  std::int64_t n = iteration_budget_ / per;
  if (iteration_ == 1) {
    // At least two configurations on first_test seeds, from the whole budget if need be.
    n = std::max<std::int64_t>(n, std::min<std::int64_t>(2, (budget_ - spent_) / settings_.first_test));
    iteration_budget_ = std::max(iteration_budget_, std::min(budget_ - spent_, n * settings_.first_test));
  }
  const std::int64_t fresh = n - std::int64_t(elites_.size());
  if (fresh <= 0 || (remaining <= 0 && iteration_ > 1)) {
    start_post_selection();
    return;
  }
  const std::size_t before = pool_.size();
  if (iteration_ == 1) add_initial(int(fresh));
  else add_children(int(fresh));
  new_this_iteration_ = int(pool_.size() - before);
  for (std::int64_t id : elites_) pool_[std::size_t(id - 1)].alive = true;
  if (new_this_iteration_ == 0 || alive().size() < 2) {  // nothing new to race (a small, finite domain)
    if (elites_.empty()) elites_ = alive();
    start_post_selection();
    return;
  }
  if (exhausted_) {
    // Every point of the domain races now and none can be added later: the
    // race gets the whole budget and goes on to a single survivor.
    iteration_budget_ = budget_ - spent_;
    n_survivors_ = 1;
  }
  begin_race();
}

// The elites of the last race have run few seeds each (a race spreads its
// budget over many configurations), so the best of them is often the luckiest:
// the budget kept back races them alone on further seeds, to one survivor.
void Race::start_post_selection() {
  if (post_selection_ || elites_.size() < 2 || budget_ - spent_ < std::int64_t(elites_.size())) {
    --iteration_;  // it never raced
    done_ = true;
    return;
  }
  post_selection_ = true;
  for (Candidate& c : pool_) c.alive = false;
  for (std::int64_t id : elites_) pool_[std::size_t(id - 1)].alive = true;
  iteration_budget_ = budget_ - spent_;
  n_survivors_ = 1;
  begin_race();
}

void Race::begin_race() {
  racing_ = true;
  seeds_ = 0;
  iteration_spent_ = 0;
}

void Race::end_iteration() {
  const std::vector<std::int64_t> order = ranked(alive());
  elites_.assign(order.begin(), order.begin() + std::min<std::ptrdiff_t>(n_survivors_, std::ptrdiff_t(order.size())));
  for (Candidate& c : pool_) c.alive = false;
  for (std::int64_t id : elites_) pool_[std::size_t(id - 1)].alive = true;
  racing_ = false;
  if (spent_ >= budget_ || post_selection_) done_ = true;
}

void Race::eliminate() {
  const std::vector<std::int64_t> ids = alive();
  if (ids.size() < 2) return;
  const std::vector<double> m = costs_by_seed(ids);
  std::vector<bool> keep;
  if (settings_.test == RaceTest::friedman) {
    keep = friedman_survivors(m, std::size_t(seeds_), ids.size(), settings_.confidence);
  } else {
    // Paired Wilcoxon of each against the best by rank sum, Holm-corrected.
    const std::vector<std::int64_t> order = ranked(ids);
    const Candidate& best = candidate(order.front());
    const std::span<const double> b(best.costs.data(), std::size_t(seeds_));
    std::vector<std::pair<double, std::size_t>> p;
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (ids[k] != best.id)
        p.push_back({wilcoxon_signed_rank_p(std::span<const double>(candidate(ids[k]).costs.data(), b.size()), b), k});
    std::sort(p.begin(), p.end());
    keep.assign(ids.size(), true);
    const double alpha = 1.0 - settings_.confidence;
    for (std::size_t r = 0; r < p.size(); ++r) {
      if (p[r].first * double(p.size() - r) >= alpha) break;  // Holm: stop at the first not rejected
      keep[p[r].second] = false;
    }
  }
  // Elitist racing (irace's default): an elite that ran more seeds than this
  // race has so far is not dropped on fewer seeds than it has evidence for.
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (!keep[k] && std::int64_t(candidate(ids[k]).costs.size()) <= seeds_)
      pool_[std::size_t(ids[k] - 1)].alive = false;
}

std::vector<RaceEvaluation> Race::next() {
  while (!done_) {
    if (!racing_) {
      start_iteration();
      continue;
    }
    const std::vector<std::int64_t> ids = alive();
    const std::int64_t step = seeds_ < settings_.first_test ? settings_.first_test - seeds_ : settings_.each_test;
    pending_.clear();
    pending_seeds_ = 0;
    // Whole seeds only, within the iteration's budget.
    for (std::int64_t s = seeds_; s < seeds_ + step; ++s) {
      std::vector<RaceEvaluation> add;
      for (std::int64_t id : ids) {
        const Candidate& c = candidate(id);
        if (std::size_t(s) >= c.costs.size() || std::isnan(c.costs[std::size_t(s)])) add.push_back({id, s, iteration_});
      }
      if (iteration_spent_ + std::int64_t(pending_.size() + add.size()) > iteration_budget_) break;
      pending_.insert(pending_.end(), add.begin(), add.end());
      ++pending_seeds_;
    }
    if (pending_seeds_ == 0) {
      end_iteration();
      continue;
    }
    if (!pending_.empty()) return pending_;
    take({});  // the elites alone, on seeds they ran already
  }
  return {};
}

void Race::take(std::span<const double> costs) {
  if (costs.size() != pending_.size())
    throw std::invalid_argument("Race::take: " + std::to_string(costs.size()) + " costs for " +
                                std::to_string(pending_.size()) + " evaluations");
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    Candidate& c = pool_[std::size_t(pending_[k].config - 1)];
    const auto s = std::size_t(pending_[k].seed);
    if (c.costs.size() <= s) c.costs.resize(s + 1, std::numeric_limits<double>::quiet_NaN());
    c.costs[s] = costs[k];
  }
  const auto n = std::int64_t(pending_.size());
  spent_ += n;
  iteration_spent_ += n;
  seeds_ += pending_seeds_;
  pending_.clear();
  pending_seeds_ = 0;
  if (seeds_ >= settings_.first_test && (seeds_ - settings_.first_test) % settings_.each_test == 0) eliminate();
  if (std::int64_t(alive().size()) <= n_survivors_ || iteration_spent_ >= iteration_budget_) end_iteration();
}

}  // namespace chaosweep
