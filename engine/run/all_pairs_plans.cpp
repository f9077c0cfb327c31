#include "engine/run/all_pairs_plans.hpp"

#include <tbb/task_arena.h>

#include "engine/run/parallel_indices.hpp"

namespace chaosweep {

std::vector<seed002::PlanRow> all_pairs_plans(const seed002::Roadmap& rm, const std::vector<int>& sources,
                                              int threads) {
  std::vector<seed002::PlanRow> rows(sources.size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  parallel_indices(arena, sources.size(), [&](std::size_t i) { rows[i] = seed002::all_plans_from(rm, sources[i]); });
  return rows;
}

}  // namespace chaosweep
