#include "engine/run/sweep_summary.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "engine/run/progress.hpp"

namespace chaosweep {

namespace {
// Positive doubles order like their bit patterns: dropping all but 10
// mantissa bits gives bins of relative width 2^-10.
constexpr int drop_bits = 42;
std::uint64_t bin_of(double t) { return std::bit_cast<std::uint64_t>(t) >> drop_bits; }
double bin_middle(std::uint64_t b) {
  return 0.5 * (std::bit_cast<double>(b << drop_bits) + std::bit_cast<double>((b + 1) << drop_bits));
}
}  // namespace

void SweepSummary::bin(double t) { ++bins_[bin_of(std::max(t, 0.0))]; }

void SweepSummary::add(const RunRow& row) {
  ++runs_;
  ++by_status_[std::size_t(row.result.status)];
  if (row.result.status != Status::ok) return;
  const double t = row.result.coverage_time;
  if (std::isnan(best_time_) || t < best_time_) {  // NaN until the first ok run
    best_time_ = t;
    best_id_ = row.tuple.run_id;
  }
  if (bins_.empty() && ok_times_.size() < exact_limit) {
    ok_times_.push_back(t);
    return;
  }
  if (bins_.empty()) {  // past the limit: from now on, bins only
    for (double v : ok_times_) bin(v);
    std::vector<double>().swap(ok_times_);
  }
  bin(t);
}

double SweepSummary::median_time() const {
  const std::int64_t ok = count(Status::ok);
  if (ok == 0) return NAN;
  if (bins_.empty()) {
    std::vector<double> v = ok_times_;
    const std::size_t m = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + m, v.end());
    if (v.size() % 2) return v[m];
    const double upper = v[m];
    std::nth_element(v.begin(), v.begin() + m - 1, v.end());
    return 0.5 * (v[m - 1] + upper);
  }
  // The middle of the bins holding ranks (ok-1)/2 and ok/2.
  const std::int64_t lo_rank = (ok - 1) / 2, hi_rank = ok / 2;
  double lo = NAN, hi = NAN;
  std::int64_t seen = 0;
  for (const auto& [b, n] : bins_) {
    if (std::isnan(lo) && lo_rank < seen + n) lo = bin_middle(b);
    if (hi_rank < seen + n) {
      hi = bin_middle(b);
      break;
    }
    seen += n;
  }
  return 0.5 * (lo + hi);
}

std::string SweepSummary::text() const {
  char buf[512];
  std::string s;
  std::snprintf(buf, sizeof buf, "runs        %lld\n", (long long)runs_);
  s += buf;
  std::snprintf(
      buf, sizeof buf,
      "ok          %lld\nfailed      %lld  (timeout %lld, stuck %lld, diverged %lld, invalid %lld, error %lld)\n",
      (long long)count(Status::ok), (long long)(runs_ - count(Status::ok)), (long long)count(Status::timeout),
      (long long)count(Status::stuck), (long long)count(Status::diverged), (long long)count(Status::invalid),
      (long long)count(Status::error));
  s += buf;
  if (count(Status::timeout) + count(Status::stuck) > 0)
    s += "            (timeout/stuck: coverage stalled below dc within the budget, e.g. a regular orbit)\n";
  if (count(Status::ok) == 0) {
    s += "coverage time: no run reached the desired coverage\n";
  } else {
    std::snprintf(buf, sizeof buf, "best CT     %.1f s  (run_id %lld)\nmedian CT   %.1f s  (over ok runs%s)\n",
                  best_time(), (long long)best_id_, median_time(), median_is_exact() ? "" : "; within 0.05%");
    s += buf;
  }
  if (std::isfinite(elapsed_)) {
    std::snprintf(buf, sizeof buf, "elapsed     %.1f s (wall clock%s)\n", elapsed_,
                  elapsed_ >= 60 ? (", " + duration_text(elapsed_)).c_str() : "");
    s += buf;
  }
  return s;
}

}  // namespace chaosweep
