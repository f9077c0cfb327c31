#pragma once
// Which compiled kernel width runs: portable scalar (width 1), AVX2 (x86-64-v3,
// 4 doubles) or AVX-512 (x86-64-v4, 8 doubles). Results are bit-identical
// across targets; only speed differs.
#include <optional>
#include <string_view>

namespace chaosweep {

enum class SimdTarget { scalar, avx2, avx512 };

const char* to_string(SimdTarget t);
std::optional<SimdTarget> parse_simd_target(std::string_view name);
int lane_width(SimdTarget t);
int lane_count(SimdTarget t);  // lanes one driver keeps in flight (interleaved vectors)
bool cpu_supports(SimdTarget t);
SimdTarget best_simd_target();  // the widest the CPU runs

}  // namespace chaosweep
