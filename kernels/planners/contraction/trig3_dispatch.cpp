#include "kernels/planners/contraction/trig3_fast.hpp"

namespace chaosweep {

// The features x86-64-v3 adds that the kernels rely on (as cpu_supports in
// kernels/lanes/simd_target.cpp, which this layer cannot include).
bool trig3_avx2_usable() {
  static const bool usable = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
           __builtin_cpu_supports("bmi2");
  }();
  return usable;
}

}  // namespace chaosweep
