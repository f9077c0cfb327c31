#include "arnold_planner.hpp"

#include <cmath>

#include "arnold_flow.hpp"
#include "metrics.hpp"
#include "robot_motion.hpp"

namespace chaosweep {

namespace {
bool finite(const Vec3<double>& u) {
  return std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z);
}
}  // namespace

void run_arnold(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r) {
  const long needed = cells_needed(p.dc, grid.free_cells());
  const double budget = p.max_time > 0 ? p.max_time : p.max_pr * r.t_opt;
  const ArnoldCoeffs<double> k{p.A, p.B, p.C};
  const HeadingSelect<double> hs = heading_select(p.ds_index);
  const bool doubling = p.integrator == Integrator::rk4_doubling;

  Vec3<double> u{wrap_pi(p.ic_x), wrap_pi(p.ic_y), wrap_pi(p.ic_z)};
  RobotMotion robot(p, env, grid);
  double h = p.dt, t = 0.0, t_last_new = 0.0;
  long last_visited = grid.visited_cells();

  for (;;) {
    if (grid.visited_cells() >= needed) {
      r.status = Status::ok;
      r.coverage_time = t;
      break;
    }
    if (t >= budget) {
      r.status = Status::timeout;
      break;
    }
    if (p.stuck_time > 0 && t - t_last_new >= p.stuck_time) {
      r.status = Status::stuck;
      break;
    }

    const double h_pos = p.f * p.v * h;
    const Rk4Step<double> full = rk4_step(u, k, hs, h, h_pos);
    if (!doubling) {
      robot.move(full.dX, full.dY);
      u = full.u;
      t += p.f * h;
      r.steps += 1;
    } else {
      const double hh = 0.5 * h, hh_pos = 0.5 * h_pos;
      const Rk4Step<double> a = rk4_step(u, k, hs, hh, hh_pos);
      const Rk4Step<double> b = rk4_step(a.u, k, hs, hh, hh_pos);
      if (std::fabs(full.dX - (a.dX + b.dX)) > p.ep || std::fabs(full.dY - (a.dY + b.dY)) > p.ep) {
        robot.move(a.dX, a.dY);
        robot.move(b.dX, b.dY);
        u = b.u;
        t += p.f * h;
        h = hh;
        r.steps += 2;
        r.dt_halvings += 1;
        if (h < p.dt_min) {
          r.status = Status::diverged;
          r.message = "step doubling shrank dt below dt_min";
          break;
        }
      } else {
        robot.move(full.dX, full.dY);
        u = full.u;
        t += p.f * h;
        r.steps += 1;
      }
    }

    if (!finite(u) || !std::isfinite(robot.x()) || !std::isfinite(robot.y())) {
      r.status = Status::diverged;
      r.message = "non-finite state";
      break;
    }
    if (grid.visited_cells() != last_visited) {
      last_visited = grid.visited_cells();
      t_last_new = t;
    }
  }
  r.t_end = t;
  r.final_x = robot.x();
  r.final_y = robot.y();
}

}  // namespace chaosweep
