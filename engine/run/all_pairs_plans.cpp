#include "engine/run/all_pairs_plans.hpp"

#include "engine/run/parallel_indices.hpp"

namespace chaosweep {

std::vector<bouncing_paper::PlanRow> all_pairs_plans(const bouncing_paper::Roadmap& rm, const std::vector<int>& sources,
                                                     int threads) {
  std::vector<bouncing_paper::PlanRow> rows(sources.size());
  parallel_indices(threads, sources.size(),
                   [&](std::size_t i) { rows[i] = bouncing_paper::all_plans_from(rm, sources[i]); });
  return rows;
}

}  // namespace chaosweep
