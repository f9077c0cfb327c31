#include "sweep_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace chaosweep {

void SweepSummary::add(const RunRow& row) {
  ++runs_;
  ++by_status_[std::size_t(row.result.status)];
  if (row.result.status == Status::ok) {
    if (ok_times_.empty() || row.result.coverage_time < best_time()) best_id_ = row.tuple.run_id;
    ok_times_.push_back(row.result.coverage_time);
  }
}

double SweepSummary::best_time() const {
  if (ok_times_.empty()) return NAN;
  return *std::min_element(ok_times_.begin(), ok_times_.end());
}

double SweepSummary::median_time() const {
  if (ok_times_.empty()) return NAN;
  std::vector<double> v = ok_times_;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  if (v.size() % 2) return v[m];
  const double upper = v[m];
  std::nth_element(v.begin(), v.begin() + m - 1, v.end());
  return 0.5 * (v[m - 1] + upper);
}

std::string SweepSummary::text() const {
  char buf[512];
  std::string s;
  std::snprintf(buf, sizeof buf, "runs        %lld\n", (long long)runs_);
  s += buf;
  std::snprintf(buf, sizeof buf, "ok          %lld\nfailed      %lld  (timeout %lld, stuck %lld, diverged %lld, invalid %lld, error %lld)\n",
                (long long)count(Status::ok), (long long)(runs_ - count(Status::ok)),
                (long long)count(Status::timeout), (long long)count(Status::stuck),
                (long long)count(Status::diverged), (long long)count(Status::invalid),
                (long long)count(Status::error));
  s += buf;
  if (count(Status::timeout) + count(Status::stuck) > 0)
    s += "            (timeout/stuck: coverage stalled below dc within the budget, e.g. a regular orbit)\n";
  if (ok_times_.empty()) {
    s += "coverage time: no run reached the desired coverage\n";
  } else {
    std::snprintf(buf, sizeof buf, "best CT     %.1f s  (run_id %lld)\nmedian CT   %.1f s  (over ok runs)\n",
                  best_time(), (long long)best_id_, median_time());
    s += buf;
  }
  return s;
}

}  // namespace chaosweep
