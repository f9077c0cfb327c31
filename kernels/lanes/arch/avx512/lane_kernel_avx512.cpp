// Width 8 (AVX-512), two vectors per pass, stage by stage in turn; this file alone is compiled with -march=x86-64-v4.
// It must call nothing inline that baseline code also instantiates: only the
// vector-typed templates live here (see tests/check_simd_symbols.sh).
// The vector lane types' overloads must be declared before the integrator
// template that calls them (its own block, so that include sorting keeps it first).
#include "kernels/math/simd_lane_math.hpp"

#include "kernels/lanes/lane_integrator.hpp"

namespace chaosweep {
void integrate_lanes_avx512(LaneArrays& a, LaneSink& sink) { integrate_lanes<lane::v8d, 2, true>(a, sink); }
}  // namespace chaosweep
