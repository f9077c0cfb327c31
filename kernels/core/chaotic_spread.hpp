#pragma once
// The chaotic spread of a run (docs/spec.md §1, "Chaotic spread"): its
// initial states perturbed by draws from its seed, shared by every planner
// driven by the Arnold flow.

#include <cstdint>

#include "kernels/core/run_params.hpp"
#include "kernels/systems/arnold_flow.hpp"

namespace chaosweep {

// Uniform in [-1, 1), advancing a splitmix64 state.
double uniform_pm1(std::uint64_t& state);

// ic + ic_jitter * uniform(-1, 1) per coordinate, drawn from `seed`.
Vec3<double> jittered_ic(const RunParams& p);

}  // namespace chaosweep
