#pragma once
// The chaotic systems the seed-000 planner family can be driven by: the
// Arnold flow (index 0, a carried system: its own step, arnold_flow.hpp) and
// the flows of flows/ and maps of maps/ (index 1, 2, ... in the order of
// `ListedSystems`). A run names its system by that index (RunParams::system;
// the spec by the system's name). Adding a system is adding its header and
// its name here: the parameter table, the scalar planner and every lane
// width take it from this list (docs/add_a_system.md).
#include "kernels/systems/chaotic_map.hpp"
#include "kernels/systems/flow.hpp"
#include "kernels/systems/flows/arnold.hpp"
#include "kernels/systems/flows/chen.hpp"
#include "kernels/systems/flows/chua.hpp"
#include "kernels/systems/flows/lorenz.hpp"
#include "kernels/systems/maps/chirikov.hpp"
#include "kernels/systems/system_info.hpp"

namespace chaosweep {

template <class... F>
struct SystemList {
  static constexpr int size = sizeof...(F);
};

using ListedSystems = SystemList<Arnold, Lorenz, Chen, Chua, Chirikov>;

inline constexpr int system_count = ListedSystems::size;

template <class F>
struct SystemTag {
  using type = F;
};

namespace system_detail {
template <class Fn, class F, class... Rest>
inline void visit(int k, Fn&& fn, SystemList<F, Rest...>) {
  if (k == 0) fn(SystemTag<F>{});
  else if constexpr (sizeof...(Rest) > 0) visit(k - 1, fn, SystemList<Rest...>{});
}
template <class Fn, class... F>
inline void each(Fn&& fn, SystemList<F...>) {
  (fn(SystemTag<F>{}), ...);
}
}  // namespace system_detail

// Calls fn(SystemTag<F>{}) for the system of index s; nothing for an index
// out of range.
template <class Fn>
inline void with_system(int s, Fn&& fn) {
  if (s >= 0 && s < system_count) system_detail::visit(s, fn, ListedSystems{});
}

// Calls fn(SystemTag<F>{}) for every listed system, in index order.
template <class Fn>
inline void for_each_system(Fn&& fn) {
  system_detail::each(fn, ListedSystems{});
}

// One step of listed system F: an RK4 step of h for a flow, one iteration
// for a map; the robot moves h_pos along the heading.
template <class F, class T>
inline SystemStep<T> system_step(const Vec3<T>& u, const SystemCoeffs<T>& k, const HeadingSelect<T>& hs, T h, T h_pos) {
  if constexpr (ChaoticMap<F>) return map_step<F>(u, k, hs, h_pos);
  else return flow_rk4_step<F>(u, k, hs, h, h_pos);
}

// One step of listed system F from state u carrying t (CarriedSystem: its
// own step in its mode for h; any other: system_step, t passed on as is).
template <class F>
inline Rk4Step<double> step_with_carry(const Vec3<double>& u, const Trig3<double>& t, const SystemCoeffs<double>& k,
                                       const HeadingSelect<double>& hs, double h, double h_pos) {
  if constexpr (CarriedSystem<F>) {
    return F::step(u, t, F::scale(k, h, h_pos), hs, F::small(k, h));
  } else {
    const SystemStep<double> s = system_step<F>(u, k, hs, h, h_pos);
    return {s.u, t, s.dX, s.dY};
  }
}

// The carry of state u for system s (CarriedSystem), else `t` unchanged.
inline Trig3<double> system_carry(int s, const Vec3<double>& u, const Trig3<double>& t) {
  Trig3<double> c = t;
  with_system(s, [&](auto tag) {
    using F = typename decltype(tag)::type;
    if constexpr (CarriedSystem<F>) c = F::carry(u);
  });
  return c;
}

// The state a run of system s starts from (system_start).
inline Vec3<double> system_start(int s, const Vec3<double>& u) {
  Vec3<double> v = u;
  with_system(s, [&](auto tag) { v = system_start<typename decltype(tag)::type>(u); });
  return v;
}

// The number of coordinates a system has (a map may have 2: its z is
// unused and DSindex 3 means nothing), and whether it is a map (one
// iteration per step: step doubling means nothing).
inline int system_dimension(int s) {
  int n = 3;
  with_system(s, [&](auto tag) {
    using F = typename decltype(tag)::type;
    if constexpr (requires { F::dimension; }) n = F::dimension;
  });
  return n;
}
inline bool system_is_map(int s) {
  bool m = false;
  with_system(s, [&](auto tag) { m = ChaoticMap<typename decltype(tag)::type>; });
  return m;
}

}  // namespace chaosweep
