#pragma once
// The kernel target this process runs: the widest the CPU supports, unless
// CHAOSWEEP_SIMD=scalar|avx2|avx512 forces one.
#include "kernels/lanes/simd_target.hpp"

namespace chaosweep {

// Throws std::runtime_error for an unknown or unsupported CHAOSWEEP_SIMD.
SimdTarget selected_simd_target();

}  // namespace chaosweep
