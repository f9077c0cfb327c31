#include "engine/spec/run_tuple.hpp"

#include <cmath>

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

}  // namespace chaosweep
