// Google Benchmark for the scalar reference kernel. Speed is reported as
// ratios measured in one run (see BENCHMARKS.md), never asserted in tests.
#include <benchmark/benchmark.h>

#include <cmath>

#include "arnold_flow.hpp"
#include "planner.hpp"
#include "sincos.hpp"

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

// One RK4 step of the Arnold + robot system (12 sincos).
void BM_rk4_step_scalar(benchmark::State& state) {
  const ArnoldCoeffs<double> k{0.5, 0.25, 0.25};
  Vec3<double> u{0, 1, 0};
  double X = 0;
  for (auto _ : state) {
    const auto st = rk4_step(u, k, heading_select(3), 0.1, 0.1);
    u = st.u;
    X += st.dX;
    benchmark::DoNotOptimize(X);
  }
}
BENCHMARK(BM_rk4_step_scalar);

// A whole run (integration, boundary, supercover marking, coverage check),
// reported per integration step.
void BM_run_original_50m_sr1(benchmark::State& state) {
  RunParams p;
  p.size_x = p.size_y = 50;
  p.sr = 1;
  p.start_x = p.start_y = 0.5;
  Environment env;
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
BENCHMARK(BM_run_original_50m_sr1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
