#pragma once
// An optional observer of a run's trajectory (for `run --trace` and figures).
// The kernels call it; they never know where the points go.
namespace chaosweep {

// chebyshev: a point on the way to a sub-goal inside a coverage rectangle;
// subgoal: the sub-goal itself; transit: a point in a transition rectangle
// (lawnmower: on the way between rectangles); move: a baseline's move (a
// random-walk step, a point of a lawnmower's lanes).
enum class SegmentKind { start, arnold, transit, logistic, chebyshev, subgoal, move };
const char* to_string(SegmentKind);

struct TracePoint {
  double t, x, y;
  SegmentKind kind;
  int ds_index;
};

class TraceSink {
 public:
  virtual ~TraceSink() = default;
  virtual void point(const TracePoint& p) = 0;
};

}  // namespace chaosweep
