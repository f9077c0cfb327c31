#pragma once
// What a sweep printed at its end: counts per status, best and median
// coverage time of the runs that reached dc.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "run_tuple.hpp"

namespace chaosweep {

class SweepSummary {
 public:
  void add(const RunRow& row);
  std::int64_t runs() const { return runs_; }
  std::int64_t count(Status s) const { return by_status_[std::size_t(s)]; }
  double best_time() const;    // NaN when no run is ok
  double median_time() const;  // NaN when no run is ok
  std::int64_t best_run_id() const { return best_id_; }
  std::string text() const;

 private:
  std::int64_t runs_ = 0, best_id_ = -1;
  std::array<std::int64_t, 6> by_status_{};
  std::vector<double> ok_times_;
};

}  // namespace chaosweep
