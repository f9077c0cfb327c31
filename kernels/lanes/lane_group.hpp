#pragma once
// What a kernel's lanes run together, a group at a time (LaneArrays::system):
// the seed-000 planner driven by a listed system (group = its index in
// system_list.hpp), or the Logistic planner (the group after them), whose
// step is the map's (LogisticMap::lane_step) and whose robot, cells and end
// checks are the Arnold planner's.
#include "kernels/systems/logistic_map.hpp"
#include "kernels/systems/system_list.hpp"

namespace chaosweep {

inline constexpr int logistic_lane_group = system_count;
inline constexpr int lane_group_count = system_count + 1;

// Calls fn(SystemTag<F>{}) for group g: a listed system, or LogisticMap.
template <class Fn>
inline void with_lane_group(int g, Fn&& fn) {
  if (g == logistic_lane_group) fn(SystemTag<LogisticMap>{});
  else with_system(g, fn);
}

}  // namespace chaosweep
