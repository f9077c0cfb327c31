// Width 4 (AVX2 + FMA), two vectors per pass, stage by stage in turn (as
// AVX-512: on an EPYC without AVX-512 the interleaved stages took 0.70-0.77x
// the time of one vector's step after the other's, BENCHMARKS.md); this file
// alone is compiled with -march=x86-64-v3.
// It must call nothing inline that baseline code also instantiates: only the
// vector-typed templates live here (see tests/check_simd_symbols.sh).
// The vector lane types' overloads must be declared before the integrator
// template that calls them (its own block, so that include sorting keeps it first).
#include "kernels/math/simd_lane_math.hpp"

#include "kernels/lanes/lane_integrator.hpp"

namespace chaosweep {
void integrate_lanes_avx2(LaneArrays& a, LaneSink& sink) { integrate_lanes<lane::v4d, 2, true>(a, sink); }
}  // namespace chaosweep
