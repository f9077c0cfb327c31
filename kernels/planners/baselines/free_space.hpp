#pragma once
// Whether a straight move keeps a point robot in the free space.
#include "kernels/core/environment.hpp"

namespace chaosweep {

// Whether the segment (x0, y0) -> (x1, y1) meets the interior of obstacle o
// (running along its edge or touching its corner does not).
bool crosses_interior(const Rect& o, double x0, double y0, double x1, double y1);

// Whether a move from (x0, y0), a free point, to (x1, y1) stays free: its end
// strictly inside the map's walls and no obstacle's interior met on the way.
bool move_stays_free(const Environment& env, double x0, double y0, double x1, double y1);

}  // namespace chaosweep
