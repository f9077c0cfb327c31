#pragma once
// The workspace a run happens in: a rectangle [0,lx] x [0,ly] with static
// axis-aligned rectangular obstacles (docs/spec.md §1). Pure data; loading from files
// is the engine's job.
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace chaosweep {

class ObstacleIndex;

struct Rect {
  double x0, y0, x1, y1;  // lower-left and upper-right corners, metres
  bool contains(double x, double y) const { return x > x0 && x < x1 && y > y0 && y < y1; }
  // The closed rectangle: its edges too.
  bool contains_closed(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

// A rectangle holding no point, closed or open.
inline constexpr Rect no_rect{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};

struct Environment {
  std::string name = "empty";
  double lx = 50.0, ly = 50.0;
  std::vector<Rect> obstacles;
  // Start point suggested by the environment (metres); a run's own start wins.
  std::optional<std::pair<double, double>> start;

  // Index of the first obstacle containing (x, y) in its interior, or -1.
  int obstacle_at(double x, double y) const;
  // Whether (x, y) lies inside an obstacle grown by fo on every side (the
  // band where Eq. 8 pushes).
  bool near_obstacle(double x, double y, double fo) const;
  double obstacle_area() const;  // area covered by obstacles, overlaps counted once

  // A grid of buckets over the obstacles, built by index_obstacles() once the
  // obstacles are final (the environment loader does): the queries above and
  // push_out_of_obstacles then look at nearby obstacles only, with the same
  // answers as a scan of them all. Used only while it covers every obstacle.
  std::shared_ptr<const ObstacleIndex> index;
  void index_obstacles();
  const ObstacleIndex* usable_index() const;  // nullptr: scan every obstacle
};

// Eq. 8: a position inside an obstacle, or within fo of it, moves to the
// obstacle's nearest face plus fo along the axis of least penetration.
// Repeats (bounded) in case the new position lies in a neighbouring obstacle.
// Returns true when the point was moved.
bool push_out_of_obstacles(const Environment& env, double fo, double& x, double& y);

// What keep_out_of_obstacles did: moved the point at all, and how many times
// it crossed a face along each axis (odd: the axis's motion is reversed).
struct ObstacleHit {
  bool moved = false;
  int x_faces = 0, y_faces = 0;
};

// The same test and the same face as push_out_of_obstacles (least
// penetration into the obstacle grown by fo); `mirror` = false puts the
// coordinate on that face (Eq. 8 as printed, X = M_left - fo), true reflects
// it about the face (Eq. 7 applied at the obstacle: X = -X + 2 (M_left - fo)).
ObstacleHit keep_out_of_obstacles(const Environment& env, double fo, bool mirror, double& x, double& y);

// Where the lane integrators may apply Eq. 8 themselves (kernels/lanes): a
// closed box around (x, y) inside `band`, at most `reach` from it along each
// axis, that meets the grown rectangle (the obstacle grown by fo, open) of
// no obstacle but `near`: the one nearest to (x, y) when `with_near`, else
// none. keep_out_of_obstacles moves a point P of the box only when near's
// grown rectangle holds it, once, onto (mirror: about) that rectangle's face
// of least penetration (the obstacles before near in the pass do not hold
// P; those after it and the second round do not hold the point it reaches
// when that is in the box too: the rectangle is open). The box is empty (x0 > x1) when
// (x, y) lies in another grown rectangle or outside the band; near is empty
// when there is none. Other obstacles are cut off the box on the side whose
// new edge lies farthest from (x, y), not the side that keeps the most area:
// a lane keeps its box until a step ends beyond a cut edge (0.82-0.88x the
// CPU time on 50 m SR 4 five squares, BENCHMARKS.md "Boxes cut far from the
// robot").
struct ObstacleBox {
  Rect box = no_rect, near = no_rect;
};
ObstacleBox obstacle_box(const Environment& env, double fo, double x, double y, const Rect& band, double reach,
                         bool with_near);
// The reach RobotMotion's clear box gets, in cells of the coverage grid (the
// lanes' boxes reach across the band, lane_binding.cpp): a wide box is left
// less often; on a map of many obstacles a box is cut much smaller anyway.
inline constexpr double obstacle_box_reach_cells = 16;

}  // namespace chaosweep
