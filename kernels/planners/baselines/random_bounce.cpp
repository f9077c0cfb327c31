#include "kernels/planners/baselines/random_bounce.hpp"

namespace chaosweep {

RunParams random_bounce_as_bouncing(RunParams p) {
  p.planner = Planner::bouncing;
  p.bounce_phi1 = 180, p.bounce_alpha1 = 1;
  p.bounce_phi2 = 0, p.bounce_alpha2 = 0;
  p.bounce_phi3 = 0, p.bounce_alpha3 = 0;
  p.bounce_eps = 180;  // the turn: 180 + uniform(-180, 180) degrees
  p.bounce_r = 0;      // never the exact turn
  return p;
}

}  // namespace chaosweep
