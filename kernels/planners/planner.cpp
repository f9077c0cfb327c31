#include "kernels/planners/planner.hpp"

#include <cmath>
#include <sstream>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/metrics.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/planners/arnold/planner_run.hpp"
#include "kernels/planners/baselines/lawnmower.hpp"
#include "kernels/planners/baselines/random_bounce.hpp"
#include "kernels/planners/baselines/random_walk.hpp"
#include "kernels/planners/bouncing/bouncing_run.hpp"
#include "kernels/planners/chebyshev/chebyshev_run.hpp"
#include "kernels/planners/contraction/contraction_run.hpp"

namespace chaosweep {

namespace {
// Bounds the grid's memory (one byte per cell) for absurd size/sr pairs.
constexpr double max_cells = 1 << 28;

std::string fmt(double v) { return format_number(v); }

// A system's coefficients are set only for a system that has them; a map
// of two coordinates has no z to steer by or start from, and one iteration
// per step has no half step to double.
std::string check_system(const RunParams& p) {
  const std::string sys = "system = " + std::string(system_name(p.system));
  if (p.system != arnold_system && p.planner != Planner::arnold)
    return sys + " drives only planner = arnold (planner = " + to_string(p.planner) + " has its own system)";
  if (system_dimension(p.system) == 2 && p.ds_index == 3)
    return "ds_index = 3 but " + sys + " has two coordinates: ds_index must be 1 (x) or 2 (y)";
  if (system_dimension(p.system) == 2 && !std::isnan(p.ic_z) && p.ic_z != 0.0)  // rows record its z as 0
    return "ic_z = " + fmt(p.ic_z) + " but " + sys + " has two coordinates (x, y): ic_z must be unset or 0";
  if (system_is_map(p.system) && p.integrator == Integrator::rk4_doubling)
    return "integrator = rk4-doubling but " + sys + " is a map (one iteration per step): use integrator = rk4";
  const SystemDefaults d = system_defaults(p.system);
  const SystemCoeffs<double> set = set_system_coeffs(p);
  for (int k = 0; k < 4; ++k) {
    if (std::isnan(set.at(k)) || k < d.count) continue;
    const std::string name = std::string("sys_") + char('a' + k);
    if (d.count == 0) return name + " is set but " + sys + " has no sys_* coefficients (the Arnold flow takes A, B, C)";
    std::string have;
    for (int i = 0; i < d.count; ++i) have += std::string(i ? ", " : "") + d.names[i];
    return name + " is set but " + sys + " has " + std::to_string(d.count) + " coefficients (" + have + " as sys_a.." +
           char('a' + d.count - 1) + ")";
  }
  return {};
}
}  // namespace

std::string validate_run(const RunParams& p, const Environment& env) {
  if (std::string e = check_ranges(p); !e.empty()) return e;
  if (std::string e = check_system(p); !e.empty()) return e;
  if (!(env.lx > 0 && env.ly > 0)) return "environment '" + env.name + "' has no area";
  if ((env.lx / p.sr) * (env.ly / p.sr) > max_cells)
    return "sr = " + fmt(p.sr) + " gives more than 2^28 cells on a " + fmt(env.lx) + " x " + fmt(env.ly) +
           " m map: raise sr or shrink the map";
  if (p.boundary == Boundary::mirror && !(2 * p.fo < env.lx && 2 * p.fo < env.ly))
    return "fo = " + fmt(p.fo) + " must be less than half the map side (" + fmt(std::min(env.lx, env.ly) / 2) + ")";
  if (!(std::isfinite(p.start_x) && std::isfinite(p.start_y)))
    return "start is unset: give start_x/start_y or an environment with a start";
  if (p.start_x < 0 || p.start_x > env.lx || p.start_y < 0 || p.start_y > env.ly)
    return "start (" + fmt(p.start_x) + ", " + fmt(p.start_y) + ") is outside the map [0, " + fmt(env.lx) + "] x [0, " +
           fmt(env.ly) + "]";
  if (int k = env.obstacle_at(p.start_x, p.start_y); k >= 0)
    return "start (" + fmt(p.start_x) + ", " + fmt(p.start_y) + ") lies inside obstacle #" + std::to_string(k) +
           " of environment '" + env.name + "'";
  if (p.planner == Planner::chebyshev) return validate_chebyshev(p, env);
  if (p.planner == Planner::contraction) return validate_contraction(p, env);
  if (p.planner == Planner::bouncing) return validate_bouncing(p);
  if (p.planner == Planner::random_walk) return validate_random_walk(p, env);
  if (p.planner == Planner::lawnmower) return validate_lawnmower(p, env);
  return {};
}

RunResult run_planner(const RunParams& p, const Environment& env) { return run_planner(p, env, nullptr); }

bool prepare_run(const RunParams& p, const Environment& env, std::optional<CoverageGrid>& grid, RunResult& r) {
  r = RunResult{};
  grid.reset();
  r.message = validate_run(p, env);
  if (!r.message.empty()) {
    r.status = Status::invalid;
    return false;
  }
  grid.emplace(env, p.sr);
  r.free_cells = grid->free_cells();
  if (r.free_cells == 0) {
    r.status = Status::invalid;
    r.message = "environment '" + env.name + "' has no free cell";
    return false;
  }
  r.t_opt = t_opt(p.dc, env.lx * env.ly - env.obstacle_area(), p.sr, p.v);
  grid->count_cover_times(cells_needed(p, *grid));
  return true;
}

void conclude_run(const RunParams& p, const CoverageGrid& grid, RunResult& r) {
  r.visited_cells = grid.visited_cells();
  r.final_coverage = coverage_rate(p, grid, grid.visited_cells());
  r.visit_evenness = visit_evenness(grid);
  r.turn_entropy = turn_entropy(grid);
  r.coverage_area = coverage_area(grid, r.t_end, run_budget(p, r.t_opt), r.t_opt);
  if (r.status == Status::ok) r.pr = r.coverage_time / r.t_opt;
}

RunResult run_planner(const RunParams& p, const Environment& env, TraceSink* trace) {
  RunResult r;
  std::optional<CoverageGrid> grid;
  if (!prepare_run(p, env, grid, r)) return r;
  if (p.planner == Planner::chebyshev) run_chebyshev(p, env, *grid, r, trace);
  else if (p.planner == Planner::contraction) run_contraction(p, env, *grid, r, trace);
  else if (p.planner == Planner::bouncing) run_bouncing(p, env, *grid, r, trace);
  else if (p.planner == Planner::random_walk) run_random_walk(p, env, *grid, r, trace);
  else if (p.planner == Planner::random_bounce) run_bouncing(random_bounce_as_bouncing(p), env, *grid, r, trace);
  else if (p.planner == Planner::lawnmower) run_lawnmower(p, env, *grid, r, trace);
  else PlannerRun(p, env, *grid, r, trace).run();
  conclude_run(p, *grid, r);
  return r;
}

}  // namespace chaosweep
