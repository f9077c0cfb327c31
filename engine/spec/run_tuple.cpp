#include "engine/spec/run_tuple.hpp"

#include <chrono>
#include <cmath>

#include "kernels/planners/planner.hpp"

namespace chaosweep {

RunTuple resolve_run(std::int64_t run_id, const RunSpec& spec, EnvironmentCache& cache) {
  RunTuple t;
  t.run_id = run_id;
  t.env_spec = spec.env;
  t.label = spec.label;
  t.params = spec.params;
  t.env = cache.get(spec.env, spec.params.size_x, spec.params.size_y);
  t.params.size_x = t.env->lx;
  t.params.size_y = t.env->ly;
  if (std::isnan(t.params.start_x) || std::isnan(t.params.start_y)) {
    const auto start = t.env->start.value_or(std::pair{default_start, default_start});
    if (std::isnan(t.params.start_x)) t.params.start_x = start.first;
    if (std::isnan(t.params.start_y)) t.params.start_y = start.second;
  }
  return t;
}

RunRow evaluate(const RunTuple& t, TraceSink* trace) {
  RunRow row{t, {}};
  const auto t0 = std::chrono::steady_clock::now();
  try {
    row.result = run_planner(t.params, *t.env, trace);
  } catch (const std::exception& e) {
    row.result = RunResult{};
    row.result.status = Status::error;
    row.result.message = e.what();
  } catch (...) {
    row.result = RunResult{};
    row.result.status = Status::error;
    row.result.message = "unknown exception";
  }
  row.result.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

}  // namespace chaosweep
