#pragma once
// How the Chebyshev orbit is flattened before it becomes a sub-goal (seed
// 001); its own header so the map needs nothing of the run parameters.

namespace chaosweep {

enum class ChebTransform { none, arcsine, arccosine };

}  // namespace chaosweep
