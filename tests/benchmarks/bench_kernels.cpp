// Google Benchmark for the scalar reference kernel. Speed is reported as
// ratios measured in one run (see BENCHMARKS.md), never asserted in tests.
#include <benchmark/benchmark.h>

#include <cmath>
#include <optional>

#include "engine/spec/environment_loader.hpp"
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/lanes/lane_arrays.hpp"
#include "kernels/lanes/lane_binding.hpp"
#include "kernels/math/sincos.hpp"
#include "kernels/planners/planner.hpp"
#include "kernels/systems/arnold_flow.hpp"

using namespace chaosweep;

namespace {

void BM_sincos_ours(benchmark::State& state) {
  double x = 0.1, s = 0, c = 0;
  for (auto _ : state) {
    sincos(x, s, c);
    benchmark::DoNotOptimize(s);
    benchmark::DoNotOptimize(c);
    x = x < 3.0 ? x + 0.37 : x - 6.1;
  }
}
BENCHMARK(BM_sincos_ours);

void BM_sincos_glibc(benchmark::State& state) {
  double x = 0.1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(std::sin(x));
    benchmark::DoNotOptimize(std::cos(x));
    x = x < 3.0 ? x + 0.37 : x - 6.1;
  }
}
BENCHMARK(BM_sincos_glibc);

// One RK4 step of the Arnold + robot system (trig carried, as in a run).
void BM_rk4_step_scalar(benchmark::State& state) {
  const ArnoldCoeffs<double> k{0.5, 0.25, 0.25};
  Vec3<double> u{0, 1, 0};
  Trig3<double> t = trig3(u);
  double X = 0;
  for (auto _ : state) {
    const auto st = rk4_step(u, t, k, heading_select(3), 0.1, 0.1);
    u = st.u;
    t = st.t;
    X += st.dX;
    benchmark::DoNotOptimize(X);
  }
}
BENCHMARK(BM_rk4_step_scalar);

// Runs p on env once per iteration, reporting seconds per integration step.
void time_runs(benchmark::State& state, const RunParams& p, const Environment& env) {
  std::int64_t steps = 0;
  for (auto _ : state) {
    const RunResult r = run_planner(p, env);
    steps += r.steps;
    benchmark::DoNotOptimize(r.coverage_time);
  }
  // Seconds per step, printed with an SI prefix (e.g. 540n).
  state.counters["s_per_step"] =
      benchmark::Counter(double(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// A whole run (integration, boundary, supercover marking, coverage check),
// reported per integration step.
void BM_run_original_50m_sr1(benchmark::State& state) {
  RunParams p;
  p.size_x = p.size_y = 50;
  p.sr = 1;
  p.start_x = p.start_y = 0.5;
  time_runs(state, p, Environment{});
}
BENCHMARK(BM_run_original_50m_sr1)->Unit(benchmark::kMillisecond);

// A 100 m map of n 0.5 m squares on a 1.05 m pitch (issue 18: 9,000 of them
// took over 100 s before the first step), indexed as the loader indexes it.
Environment many_squares(int n) {
  Environment env;
  env.lx = env.ly = 100;
  for (int k = 0; k < n; ++k) {
    const double x = (k / 95) * 1.05 + 0.2, y = (k % 95) * 1.05 + 0.2;
    env.obstacles.push_back({x, y, x + 0.5, y + 0.5});
  }
  env.index_obstacles();
  return env;
}

// The geometry a run sets up before its first step: free area, blocked
// cells, the first obstacle box of a lane (from a map's corner).
void BM_obstacle_setup(benchmark::State& state) {
  const Environment env = many_squares(int(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(env.obstacle_area());
    const CoverageGrid grid(env, 1.0);
    benchmark::DoNotOptimize(grid.free_cells());
    benchmark::DoNotOptimize(obstacle_box(env, 0.5, 0.5, 0.5, {0.5, 0.5, env.lx - 0.5, env.ly - 0.5}, 16, true).box.x1);
  }
}
BENCHMARK(BM_obstacle_setup)->Arg(5)->Arg(1000)->Arg(9000)->Unit(benchmark::kMillisecond);

// A short run among them (most steps end near an obstacle: the scalar
// planner and Eq. 8's push-out), reported per integration step.
void BM_run_among_obstacles(benchmark::State& state) {
  const Environment env = many_squares(int(state.range(0)));
  RunParams p;
  p.size_x = p.size_y = 100;
  p.sr = 2;
  p.start_x = p.start_y = 0.1;
  p.max_time = 500;
  time_runs(state, p, env);
}
BENCHMARK(BM_run_among_obstacles)->Arg(5)->Arg(1000)->Arg(9000)->Unit(benchmark::kMillisecond);

// A lane run's setup on a 200 m SR 1 map (issue 20: 1.1-1.5 ms), everything
// before its first step: validation, grid, free area, the zones (map zoning,
// arg 1), the segment's window, the cells clear of Eq. 8. Arg 0: open (0)
// or five squares (1).
void BM_run_setup_200m_sr1(benchmark::State& state) {
  const Environment env = load_environment(state.range(0) ? "five_squares" : "no_obstacles", 200, 200);
  RunParams p;
  p.size_x = p.size_y = 200;
  p.sr = 1;
  p.start_x = p.start_y = 0.5;
  p.map_zoning = state.range(1) != 0;
  LaneArrays a;
  a.lanes = 1;
  for (auto _ : state) {
    std::optional<CoverageGrid> grid;
    RunResult r;
    if (!prepare_run(p, env, grid, r)) return state.SkipWithError(r.message.c_str());
    LaneBinding run(p, env, *grid, r);
    run.run().start();
    run.write_lane(a, 0);
    benchmark::DoNotOptimize(a.X[0]);
  }
}
BENCHMARK(BM_run_setup_200m_sr1)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);
// The three other planners on their shipped specs' maps (experiments/seed00x.toml),
// one whole run each (issue 20: Chebyshev's hypot per move, the bouncing
// robot's sincos per move, the contraction planner's portable sincos).
void BM_run_chebyshev(benchmark::State& state) {
  RunParams p;
  p.planner = Planner::chebyshev;
  p.size_x = p.size_y = 10;
  p.sr = 0.5;
  p.start_x = 1, p.start_y = 8;
  p.cheb_k = 6;
  p.dc = 0.9;
  time_runs(state, p, load_environment("cheb_case1", 10, 10));
}
BENCHMARK(BM_run_chebyshev)->Unit(benchmark::kMillisecond);

void BM_run_bouncing(benchmark::State& state) {
  RunParams p;
  p.planner = Planner::bouncing;
  p.sr = 1;
  p.step = 0.25;
  p.max_time = 200000;
  p.seed = 7;
  const Environment env = load_environment("seed002_map", 50, 50);
  p.size_x = env.lx, p.size_y = env.ly;
  p.start_x = env.start->first, p.start_y = env.start->second;
  time_runs(state, p, env);
}
BENCHMARK(BM_run_bouncing)->Unit(benchmark::kMillisecond);

// Arg: c3_n of one mapped trajectory (seed003.toml's table 3 range).
void BM_run_contraction_map(benchmark::State& state) {
  RunParams p;
  p.planner = Planner::contraction;
  p.size_x = p.size_y = 20;
  p.sr = 1;
  p.A = 1, p.B = 0.5, p.C = 0.5;
  p.ic_x = 4, p.ic_y = 3.5, p.ic_z = 0;
  p.start_x = p.start_y = 10;
  p.c3_mode = ContractionMode::map;
  p.c3_n = int(state.range(0));
  Environment env;
  env.lx = env.ly = 20;
  time_runs(state, p, env);
}
BENCHMARK(BM_run_contraction_map)->Arg(800)->Arg(19200)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

// The lane integrators alone: a sink that only counts, so this is the RK4
// step plus the vectorised fast path, per lane-step, at each width.
namespace {
// Every lane ends a segment at its 1000th step (niter), which calls the sink.
struct CountingSink : chaosweep::LaneSink {
  bool post_step() override { return false; }
};

template <void (*Integrate)(chaosweep::LaneArrays&, chaosweep::LaneSink&)>
void BM_lane_kernel(benchmark::State& state) {
  using namespace chaosweep;
  const int lanes = int(state.range(0));
  LaneArrays a;
  a.lanes = lanes;
  a.active = (1u << lanes) - 1;
  for (int l = 0; l < lanes; ++l) {
    a.x[l] = 0.01 * l;
    a.y[l] = 1.0;
    a.z[l] = 0.0;
    a.sx[l] = std::sin(a.x[l]);
    a.cx[l] = std::cos(a.x[l]);
    a.sy[l] = std::sin(1.0);
    a.cy[l] = std::cos(1.0);
    a.sz[l] = 0.0;
    a.cz[l] = 1.0;
    a.kA[l] = 0.025;
    a.kB[l] = 0.0125;
    a.kC[l] = 0.0125;
    a.pos6[l] = 0.1 / 6;
    a.small[l] = 1;  // A, B, C = 0.5, 0.25, 0.25; h = 0.1
    a.X[l] = a.Y[l] = 25;
    a.t[l] = 0;
    a.fh[l] = 0.1;
    a.budget[l] = 1e300;
    a.stuck_time[l] = 1e300;
    a.t_last_new[l] = 0;
    a.seg_step[l] = 0;
    a.niter[l] = 1000;
    a.steps[l] = 0;
    a.lo_x[l] = a.lo_y[l] = -1e300;
    a.hi_x[l] = a.hi_y[l] = 1e300;
    a.inv_cell[l] = 0;
    a.max_i[l] = a.max_j[l] = 0;
    a.cell_i[l] = a.cell_j[l] = 0;
    a.fast[l] = 1;
    a.fold[l] = a.UX[l] = a.UY[l] = 0;
    a.obstacles[l] = false;
  }
  CountingSink sink;
  for (auto _ : state) {
    for (int l = 0; l < lanes; ++l) a.seg_step[l] = 0;
    Integrate(a, sink);
  }
  state.counters["ns_per_lane_step"] = benchmark::Counter(double(state.iterations()) * 1000 * lanes,
                                                          benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
}  // namespace
BENCHMARK(BM_lane_kernel<chaosweep::integrate_lanes_scalar>)->Arg(4);
BENCHMARK(BM_lane_kernel<chaosweep::integrate_lanes_avx2>)->Arg(8);
BENCHMARK(BM_lane_kernel<chaosweep::integrate_lanes_avx512>)->Arg(16);
