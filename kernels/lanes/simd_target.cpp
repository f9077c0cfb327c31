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
    case SimdTarget::avx2:
      return __builtin_cpu_supports("x86-64-v3");
    case SimdTarget::avx512:
      return __builtin_cpu_supports("x86-64-v4");
  }
  return false;
}

SimdTarget best_simd_target() {
  if (cpu_supports(SimdTarget::avx512)) return SimdTarget::avx512;
  if (cpu_supports(SimdTarget::avx2)) return SimdTarget::avx2;
  return SimdTarget::scalar;
}

}  // namespace chaosweep
