#include "engine/run/all_pairs_plans.hpp"

#include <tbb/task_arena.h>

#include "engine/run/parallel_indices.hpp"

namespace chaosweep {

std::vector<bouncing_paper::PlanRow> all_pairs_plans(const bouncing_paper::Roadmap& rm, const std::vector<int>& sources,
                                              int threads) {
  std::vector<bouncing_paper::PlanRow> rows(sources.size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  parallel_indices(arena, sources.size(), [&](std::size_t i) { rows[i] = bouncing_paper::all_plans_from(rm, sources[i]); });
  return rows;
}

}  // namespace chaosweep
