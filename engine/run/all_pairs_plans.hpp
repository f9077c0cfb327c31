#pragma once
// Seed 002, Algorithm 2: minimum navigation plans from many sources, one
// Dijkstra tree per source run in parallel on oneTBB; row i holds source i's
// plans (slot i, as every batch evaluator here), so the result never depends
// on the thread count.
#include <vector>

#include "kernels/planners/bouncing/roadmap.hpp"

namespace chaosweep {

std::vector<bouncing_paper::PlanRow> all_pairs_plans(const bouncing_paper::Roadmap& rm, const std::vector<int>& sources,
                                                     int threads = 0);

}  // namespace chaosweep
