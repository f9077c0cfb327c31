#pragma once
// What a chaotic map driving the seed-000 planner family is, and its step. A
// map is a struct with
//   static constexpr const char* name;                   // its spec name
//   static constexpr SystemDefaults defaults;            // coefficients, initial state
//   static constexpr int dimension;                      // 2: z is unused (stays 0)
//   static constexpr double heading_scale[3];            // radians per unit of x, y, z
//   template <class T> static Vec3<T> iterate(const Vec3<T>& u, const SystemCoeffs<T>& k);
// One step of the planner is one iteration: the robot moves f v dt along the
// heading heading_scale[d] * u_d of the state it leaves (d the DSindex
// coordinate), then the state iterates. A map's coordinates are not angles:
// the scale spreads the attractor's range of the coordinate over the circle,
// as seed 001 maps its Chebyshev iterates onto the workplace.
// kernels/systems/maps/ holds the maps.
#include <concepts>

#include "kernels/systems/system.hpp"

namespace chaosweep {

template <class F>
concept ChaoticMap = requires(const Vec3<double>& u, const SystemCoeffs<double>& k) {
  { F::iterate(u, k) } -> std::same_as<Vec3<double>>;
  F::heading_scale[0];
};

// The heading angle of a map's state u: the DSindex coordinate times its scale.
template <ChaoticMap F, class T>
inline T map_heading(const Vec3<T>& u, const HeadingSelect<T>& hs) {
  const T scale =
      lane::select(hs.is_x, lane::splat<T>(F::heading_scale[0]),
                   lane::select(hs.is_y, lane::splat<T>(F::heading_scale[1]), lane::splat<T>(F::heading_scale[2])));
  return scale * heading_coordinate(u, hs);
}

// One step: the robot's displacement h_pos along the heading of u, and u's
// image.
template <ChaoticMap F, class T>
inline SystemStep<T> map_step(const Vec3<T>& u, const SystemCoeffs<T>& k, const HeadingSelect<T>& hs, T h_pos) {
  T c, s;
  heading_trig(map_heading<F>(u, hs), c, s);
  return {F::iterate(u, k), h_pos * c, h_pos * s};
}

}  // namespace chaosweep
