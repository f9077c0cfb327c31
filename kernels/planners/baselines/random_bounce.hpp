#pragma once
// The random-bounce robot (planner = random_bounce, docs/spec.md §7): drives
// straight in moves of `step` until its next move would bump a wall or an
// obstacle, then turns to a new heading drawn uniformly among those whose
// next move is free. That is seed 002's bouncing robot with one policy whose
// turn is uniform in [0, 360) (phi = 180, eps = 180, never exact): a heading
// whose first move bumps is a bump again and is drawn anew, so the heading
// the robot leaves on is uniform over the free ones (rejection sampling).
// planner.cpp runs it with run_bouncing on these parameters.
#include "kernels/core/run_params.hpp"

namespace chaosweep {

// p as the bouncing robot that is the random bounce: bounce_phi*,
// bounce_alpha*, bounce_eps and bounce_r replaced, every other field (step,
// v, seed, bounce_heading: the initial heading) kept.
RunParams random_bounce_as_bouncing(RunParams p);

}  // namespace chaosweep
