#include "engine/spec/work_bound.hpp"

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "kernels/core/run_params.hpp"

#include "kernels/core/metrics.hpp"
#include "kernels/math/splitmix.hpp"

namespace chaosweep {

namespace {

// Every key run_step_bound reads, directly or through the map (env and size
// give the free area): an axis of any other key leaves every budget as it is.
bool sets_budget(const Axis& a) {
  static const char* const keys[] = {"max_time", "max_pr", "dc",  "sr",   "v",      "planner", "dt_c",
                                     "f",        "dt",     "env", "size", "size_x", "size_y"};
  for (const std::string& k : a.keys)
    for (const char* b : keys)
      if (k == b) return true;
  return false;
}

}  // namespace

double run_step_bound(const RunParams& p, double free_area) {
  const double budget = p.max_time > 0 ? p.max_time : p.max_pr * t_opt(p.dc, free_area, p.sr, p.v);
  return std::ceil(budget / (p.planner == Planner::logistic ? p.dt_c : p.f * p.dt));
}

WorkBound bound_work(const SweepSpec& spec, EnvironmentCache& cache, std::int64_t max_exact) {
  WorkBound w;
  std::map<const Environment*, double> free_area;  // once per map: obstacle_area is the costly part
  const auto steps_of = [&](std::int64_t run_id) {
    const RunTuple t = resolve_run(run_id, spec.run(run_id), cache);
    auto it = free_area.find(t.env.get());
    if (it == free_area.end())
      it = free_area.emplace(t.env.get(), t.env->lx * t.env->ly - t.env->obstacle_area()).first;
    ++w.evaluated;
    return run_step_bound(t.params, it->second);
  };
  const std::size_t products = spec.parts.empty() ? 1 : spec.parts.size();
  for (std::size_t part = 0; part < products; ++part) {
    // The product's axes, slowest first, and the run_id step of each.
    std::vector<const Axis*> axes;
    if (!spec.parts.empty())
      for (const Axis& a : spec.parts[part].axes) axes.push_back(&a);
    for (const Axis& a : spec.axes) axes.push_back(&a);
    std::vector<std::int64_t> stride(axes.size());
    std::int64_t s = 1;
    for (std::size_t k = axes.size(); k-- > 0;) {
      stride[k] = s;
      s *= std::int64_t(axes[k]->size());
    }
    // The budget axes vary; every other axis stays at its first value and
    // multiplies: its positions repeat each budget.
    std::vector<std::size_t> varied;
    double repeats = 1, combinations = 1;
    for (std::size_t k = 0; k < axes.size(); ++k) {
      if (sets_budget(*axes[k])) {
        varied.push_back(k);
        combinations *= double(axes[k]->size());
      } else {
        repeats *= double(axes[k]->size());
      }
    }
    const std::int64_t first = spec.parts.empty() ? 0 : spec.part_offset(part);
    double sum = 0;
    if (combinations <= double(max_exact)) {
      std::vector<std::size_t> pos(varied.size(), 0);
      for (;;) {
        std::int64_t id = first;
        for (std::size_t m = 0; m < varied.size(); ++m) id += std::int64_t(pos[m]) * stride[varied[m]];
        sum += steps_of(id);
        std::size_t m = varied.size();
        while (m > 0 && ++pos[m - 1] == axes[varied[m - 1]]->size()) pos[--m] = 0;
        if (m == 0) break;
      }
    } else {
      // Too many to walk: the mean of seeded uniform draws, times their count.
      w.sampled = true;
      std::uint64_t state = 0x5eedULL + part;
      for (std::int64_t d = 0; d < max_exact; ++d) {
        std::int64_t id = first;
        for (std::size_t k : varied) id += std::int64_t(splitmix64(state) % axes[k]->size()) * stride[k];
        sum += steps_of(id);
      }
      sum *= combinations / double(max_exact);
    }
    w.steps += sum * repeats;
  }
  return w;
}

}  // namespace chaosweep
