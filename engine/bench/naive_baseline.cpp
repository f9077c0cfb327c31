#include "engine/bench/naive_baseline.hpp"

#include <cmath>

#include "kernels/core/boundary.hpp"
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/metrics.hpp"

namespace chaosweep {

namespace {
struct State {
  double x, y, z;
};
State rhs(const State& s, double A, double B, double C) {
  return {A * std::sin(s.z) + C * std::cos(s.y), B * std::sin(s.x) + A * std::cos(s.z),
          C * std::sin(s.y) + B * std::cos(s.x)};
}
double heading(const State& s, int ds) { return ds == 1 ? s.x : ds == 2 ? s.y : s.z; }
}  // namespace

long naive_original_arnold(const RunParams& p, const Environment& env) {
  CoverageGrid grid(env, p.sr);
  const long needed = cells_needed(p.dc, grid.free_cells());
  const double budget = p.max_time;
  const Vec3<double> ic = system_ic(p);
  State s{ic.x, ic.y, ic.z};
  double X = p.start_x, Y = p.start_y, t = 0;
  const double h = p.dt;
  long steps = 0;
  grid.mark_point(X, Y);
  while (grid.visited_cells() < needed && t < budget) {
    const State k1 = rhs(s, p.A, p.B, p.C);
    const State s2{s.x + h / 2 * k1.x, s.y + h / 2 * k1.y, s.z + h / 2 * k1.z};
    const State k2 = rhs(s2, p.A, p.B, p.C);
    const State s3{s.x + h / 2 * k2.x, s.y + h / 2 * k2.y, s.z + h / 2 * k2.z};
    const State k3 = rhs(s3, p.A, p.B, p.C);
    const State s4{s.x + h * k3.x, s.y + h * k3.y, s.z + h * k3.z};
    const State k4 = rhs(s4, p.A, p.B, p.C);
    const double a1 = heading(s, p.ds_index), a2 = heading(s2, p.ds_index), a3 = heading(s3, p.ds_index),
                 a4 = heading(s4, p.ds_index);
    const double dX = p.v * h / 6 * (std::cos(a1) + 2 * std::cos(a2) + 2 * std::cos(a3) + std::cos(a4));
    const double dY = p.v * h / 6 * (std::sin(a1) + 2 * std::sin(a2) + 2 * std::sin(a3) + std::sin(a4));
    s = {s.x + h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x), s.y + h / 6 * (k1.y + 2 * k2.y + 2 * k3.y + k4.y),
         s.z + h / 6 * (k1.z + 2 * k2.z + 2 * k3.z + k4.z)};
    const double px = X, py = Y;
    X = mirror_eq7(X + dX, 0.0, env.lx, p.fo);
    Y = mirror_eq7(Y + dY, 0.0, env.ly, p.fo);
    grid.mark_segment(px, py, X, Y);
    t += h;
    ++steps;
  }
  return steps;
}

}  // namespace chaosweep
