#pragma once
// What a sweep printed at its end: counts per status, best and median
// coverage time of the runs that reached dc, and the time it took.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/rows/run_row.hpp"

namespace chaosweep {

// Memory is bounded whatever the sweep's length: the median is exact up to
// exact_limit ok runs; past that, the times go into bins of relative width
// 2^-10 and the median is a bin's middle (within 0.05%).
class SweepSummary {
 public:
  static constexpr std::size_t exact_limit = std::size_t(1) << 16;  // 512 KiB of times

  void add(const RunRow& row);
  std::int64_t runs() const { return runs_; }
  std::int64_t count(Status s) const { return by_status_[std::size_t(s)]; }
  double best_time() const { return best_time_; }  // NaN when no run is ok
  double median_time() const;                      // NaN when no run is ok
  bool median_is_exact() const { return bins_.empty(); }
  std::int64_t best_run_id() const { return best_id_; }
  // The sweep's wall-clock time, which text() states when set.
  void set_elapsed(double seconds) { elapsed_ = seconds; }
  std::string text() const;

 private:
  void bin(double t);
  std::int64_t runs_ = 0, best_id_ = -1;
  double best_time_ = NAN, elapsed_ = NAN;
  std::array<std::int64_t, 6> by_status_{};
  std::vector<double> ok_times_;                // while there are <= exact_limit
  std::map<std::uint64_t, std::int64_t> bins_;  // after: count per bin
};

}  // namespace chaosweep
