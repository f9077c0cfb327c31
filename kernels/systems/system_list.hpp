#pragma once
// The chaotic systems the seed-000 planner family can be driven by: the
// Arnold flow (index 0, its own step in arnold_flow.hpp) and the flows of
// flows/ (index 1, 2, ... in the order of `Flows`). A run names its system
// by that index (RunParams::system; the spec by the flow's name). Adding a
// flow is adding its header and its name here: the parameter table, the
// scalar planner and every lane width take it from this list.
#include <string_view>

#include "kernels/systems/flows/chen.hpp"
#include "kernels/systems/flows/chua.hpp"
#include "kernels/systems/flows/lorenz.hpp"

namespace chaosweep {

template <class... F>
struct FlowList {
  static constexpr int size = sizeof...(F);
};

using Flows = FlowList<Lorenz, Chen, Chua>;

inline constexpr int arnold_system = 0;
inline constexpr double arnold_ic[3] = {0.0, 1.0, 0.0};  // docs/spec.md §2
inline constexpr int system_count = 1 + Flows::size;

template <class F>
struct FlowTag {
  using type = F;
};

namespace system_detail {
template <class Fn, class F, class... Rest>
inline void visit(int k, Fn&& fn, FlowList<F, Rest...>) {
  if (k == 0) fn(FlowTag<F>{});
  else if constexpr (sizeof...(Rest) > 0) visit(k - 1, fn, FlowList<Rest...>{});
}
template <class Fn, class... F>
inline void each(Fn&& fn, FlowList<F...>) {
  (fn(FlowTag<F>{}), ...);
}
}  // namespace system_detail

// Calls fn(FlowTag<F>{}) for the flow of system index s (1..); nothing for
// the Arnold flow (0) or an index out of range.
template <class Fn>
inline void with_flow(int s, Fn&& fn) {
  if (s >= 1 && s < system_count) system_detail::visit(s - 1, fn, Flows{});
}

// Calls fn(FlowTag<F>{}) for every flow, in index order.
template <class Fn>
inline void for_each_flow(Fn&& fn) {
  system_detail::each(fn, Flows{});
}

inline std::string_view system_name(int s) {
  std::string_view n = s == arnold_system ? "arnold" : "?";
  with_flow(s, [&](auto tag) { n = decltype(tag)::type::name; });
  return n;
}

// A system's defaults (the Arnold flow: no flow coefficients, its ic).
inline FlowDefaults system_defaults(int s) {
  FlowDefaults d{0, 0, 0, 0, 0, {"", "", "", ""}, {arnold_ic[0], arnold_ic[1], arnold_ic[2]}};
  with_flow(s, [&](auto tag) { d = decltype(tag)::type::defaults; });
  return d;
}

}  // namespace chaosweep
