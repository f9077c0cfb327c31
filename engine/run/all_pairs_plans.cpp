#include "engine/run/all_pairs_plans.hpp"

#include "engine/run/parallel_indices.hpp"

namespace chaosweep {

std::vector<seed002::PlanRow> all_pairs_plans(const seed002::Roadmap& rm, const std::vector<int>& sources,
                                              int threads) {
  std::vector<seed002::PlanRow> rows(sources.size());
  parallel_indices(threads, sources.size(), [&](std::size_t i) { rows[i] = seed002::all_plans_from(rm, sources[i]); });
  return rows;
}

}  // namespace chaosweep
