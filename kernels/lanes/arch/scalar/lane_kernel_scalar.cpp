// Width 1, portable (baseline x86-64): the same loop as the vector kernels.
#include "kernels/lanes/lane_integrator.hpp"

namespace chaosweep {
void integrate_lanes_scalar(LaneArrays& a, LaneSink& sink) { integrate_lanes<double, 4>(a, sink); }
}  // namespace chaosweep
