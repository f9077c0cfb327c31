#include "engine/run/simd_choice.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace chaosweep {

SimdTarget selected_simd_target() {
  const char* forced = std::getenv("CHAOSWEEP_SIMD");
  if (!forced || !*forced) return best_simd_target();
  const auto t = parse_simd_target(forced);
  if (!t)
    throw std::runtime_error(std::string("CHAOSWEEP_SIMD = '") + forced +
                             "' is not a target: must be one of scalar, avx2, avx512");
  if (!cpu_supports(*t))
    throw std::runtime_error(std::string("CHAOSWEEP_SIMD = ") + forced +
                             ": this CPU does not support it (best: " + to_string(best_simd_target()) + ")");
  return *t;
}

}  // namespace chaosweep
