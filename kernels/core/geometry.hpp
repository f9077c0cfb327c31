#pragma once
// A point of the map (m), shared by the planners' paths.

namespace chaosweep {

struct Point {
  double x, y;
};

}  // namespace chaosweep
