#include "kernels/planners/bouncing/bouncing_run.hpp"

#include <cmath>
#include <numbers>

#include "kernels/core/metrics.hpp"
#include "kernels/math/splitmix.hpp"

namespace chaosweep {

namespace {

struct Policy {
  double phi, alpha;
};

std::vector<Policy> policies(const RunParams& p) {
  std::vector<Policy> out;
  for (auto [phi, a] : {std::pair{p.bounce_phi1, p.bounce_alpha1}, std::pair{p.bounce_phi2, p.bounce_alpha2},
                        std::pair{p.bounce_phi3, p.bounce_alpha3}})
    if (a > 0) out.push_back({phi, a});
  return out;
}

// The free space as the robot's contact sensor sees it: the map's walls and
// the obstacles' interiors (touching an obstacle's edge is a bump too).
bool free_at(const Environment& env, double x, double y) {
  if (x <= 0 || x >= env.lx || y <= 0 || y >= env.ly) return false;
  for (const Rect& o : env.obstacles)
    if (o.contains_closed(x, y)) return false;
  return true;
}

}  // namespace

std::string validate_bouncing(const RunParams& p) {
  if (policies(p).empty()) return "bouncing robot: every policy weight bounce_alpha1..3 is 0";
  return {};
}

void run_bouncing(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace) {
  const std::vector<Policy> pol = policies(p);
  double total = 0;
  for (const Policy& q : pol) total += q.alpha;
  std::uint64_t rng = std::uint64_t(p.seed) * 0x9e3779b97f4a7c15ULL + 0x2545f4914f6cdd1dULL;
  const long needed = cells_needed(p, grid);
  const double budget = run_budget(p, r.t_opt);
  constexpr double deg = std::numbers::pi / 180.0;
  double x = p.start_x, y = p.start_y, heading = p.bounce_heading, t = 0;
  grid.mark_point(x, y);
  grid.note_time(0.0);
  if (trace) trace->point({0.0, x, y, SegmentKind::start, 0});
  // A robot boxed in (every heading bumps) would turn for ever: bounded.
  long bumps_in_a_row = 0;
  // The heading changes only at bumps: its step vector is computed there,
  // by the same calls on the same angle as before (bit-identical), not per move.
  double step_x = p.step * std::cos(heading * deg), step_y = p.step * std::sin(heading * deg);
  // Loop invariants held in locals: the calls below (grid marking) could
  // otherwise alias p for the compiler and reload and redivide every move.
  const double dt = p.step / p.v;
  // The robot's cell, carried from move to move: mark_segment's own test
  // (both ends in one cell) without recomputing the start's cell. That cell
  // is marked already (at the start or by the move into it) and this run
  // opens no Eq. 5 window, so marking it again would change nothing.
  int ci = grid.cell_x(x), cj = grid.cell_y(y);
  std::int64_t steps = 0;  // in a register, not stored through r every move
  while (true) {
    if (grid.visited_cells() >= needed) {
      r.status = Status::ok;
      r.coverage_time = t;
      break;
    }
    if (t >= budget) {
      r.status = Status::timeout;
      r.message = "budget reached before dc";
      break;
    }
    const double nx = x + step_x, ny = y + step_y;
    if (free_at(env, nx, ny)) {
      const int ni = grid.cell_x(nx), nj = grid.cell_y(ny);
      if (ni != ci || nj != cj) {
        grid.mark_segment(x, y, nx, ny);
        ci = ni, cj = nj;
      }
      x = nx, y = ny;
      t += dt;
      grid.note_time(t);  // nothing new unless the move entered a cell
      ++steps;
      bumps_in_a_row = 0;
      if (trace) trace->point({t, x, y, SegmentKind::arnold, 0});
      continue;
    }
    // Bump: draw the policy from the mixture, then the rotation.
    if (++bumps_in_a_row > 100000) {
      r.status = Status::stuck;
      r.message = "every heading bumps: the robot is boxed in";
      break;
    }
    ++r.reflections;
    double u = uniform01(rng) * total;
    std::size_t k = 0;
    while (k + 1 < pol.size() && u >= pol[k].alpha) u -= pol[k++].alpha;
    double turn = pol[k].phi;
    if (uniform01(rng) >= p.bounce_r) turn += (2.0 * uniform01(rng) - 1.0) * p.bounce_eps;
    heading = std::fmod(heading + turn, 360.0);
    step_x = p.step * std::cos(heading * deg), step_y = p.step * std::sin(heading * deg);
    if (trace) trace->point({t, x, y, SegmentKind::subgoal, int(k + 1)});
  }
  r.steps = steps;
  r.t_end = t;
  r.final_x = x, r.final_y = y;
}

}  // namespace chaosweep
