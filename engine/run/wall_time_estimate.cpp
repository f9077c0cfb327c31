#include "engine/run/wall_time_estimate.hpp"

#include <chrono>
#include <cmath>

#include "engine/spec/run_tuple.hpp"
#include "kernels/math/splitmix.hpp"

namespace chaosweep {

namespace {
// k * runs overflows int64 for runs near 1e18; GCC's 128-bit integer holds it.
__extension__ using int128 = __int128;
int128 wide(std::int64_t v) { return v; }
}  // namespace

std::vector<std::int64_t> calibration_run_ids(std::int64_t runs, std::int64_t n, std::uint64_t seed) {
  std::vector<std::int64_t> ids;
  if (n >= runs) {
    for (std::int64_t i = 0; i < runs; ++i) ids.push_back(i);
    return ids;
  }
  std::uint64_t state = seed;
  for (std::int64_t k = 0; k < n; ++k) {
    // Slice k is [k*runs/n, (k+1)*runs/n): non-empty since n < runs.
    const std::int64_t lo = std::int64_t(wide(k) * runs / n), hi = std::int64_t(wide(k + 1) * runs / n);
    ids.push_back(lo + std::min(hi - lo - 1, std::int64_t(uniform01(state) * double(hi - lo))));
  }
  return ids;
}

WallTimeEstimate extrapolate_wall_time(std::int64_t runs, double sample_seconds, const std::vector<double>& work) {
  WallTimeEstimate e;
  e.runs_drawn = std::int64_t(work.size());
  e.sample_seconds = sample_seconds;
  if (work.empty()) return e;
  const double k = double(work.size()), scale = double(runs) / k;
  e.seconds = sample_seconds * scale;
  double mean = 0, var = 0;
  for (double w : work) mean += w / k;
  for (double w : work) var += (w - mean) * (w - mean) / std::max(1.0, k - 1);
  // The sample's time is proportional to its work: the relative error of
  // the mean work is the estimate's (none when every run was drawn).
  const double rel = (work.size() == std::size_t(runs) || mean <= 0) ? 0 : 2 * std::sqrt(var / k) / mean;
  e.low = e.seconds * std::max(0.0, 1 - rel);
  e.high = e.seconds * (1 + rel);
  return e;
}

WallTimeEstimate estimate_wall_time(const SweepSpec& spec, EnvironmentCache& cache, const BatchEvaluator& evaluator,
                                    std::int64_t calibration_runs, std::uint64_t seed) {
  std::vector<RunTuple> tuples;
  for (const std::int64_t id : calibration_run_ids(spec.size(), calibration_runs, seed))
    tuples.push_back(resolve_run(id, spec.run(id), cache));
  std::vector<RunResult> results(tuples.size());
  const auto t0 = std::chrono::steady_clock::now();
  evaluator.evaluate(tuples, results);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<double> work;
  for (const RunResult& r : results) work.push_back(double(r.steps + r.transit_points));
  return extrapolate_wall_time(spec.size(), seconds, work);
}

}  // namespace chaosweep
