#include "kernels/lanes/simd_target.hpp"

namespace chaosweep {

const char* to_string(SimdTarget t) {
  switch (t) {
    case SimdTarget::scalar:
      return "scalar";
    case SimdTarget::avx2:
      return "avx2";
    case SimdTarget::avx512:
      return "avx512";
  }
  return "?";
}

std::optional<SimdTarget> parse_simd_target(std::string_view name) {
  if (name == "scalar") return SimdTarget::scalar;
  if (name == "avx2") return SimdTarget::avx2;
  if (name == "avx512") return SimdTarget::avx512;
  return std::nullopt;
}

int lane_width(SimdTarget t) { return t == SimdTarget::avx512 ? 8 : t == SimdTarget::avx2 ? 4 : 1; }

// Two interleaved vectors hide the latency of each one's dependency chain.
int lane_count(SimdTarget t) { return t == SimdTarget::scalar ? 4 : 2 * lane_width(t); }

bool cpu_supports(SimdTarget t) {
  __builtin_cpu_init();
  switch (t) {
    case SimdTarget::scalar:
      return true;
    // The kernels are built for x86-64-v3 / -v4; those level names are GCC's
    // only (clang 14 has no such feature name), so the levels are asked as the
    // features that define them beyond what every such CPU has.
    case SimdTarget::avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
             __builtin_cpu_supports("bmi2");
    case SimdTarget::avx512:
      return cpu_supports(SimdTarget::avx2) && __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512cd") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
  }
  return false;
}

SimdTarget best_simd_target() {
  if (cpu_supports(SimdTarget::avx512)) return SimdTarget::avx512;
  if (cpu_supports(SimdTarget::avx2)) return SimdTarget::avx2;
  return SimdTarget::scalar;
}

}  // namespace chaosweep
