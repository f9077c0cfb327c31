// `chaosweep plan SPEC.toml`: what a sweep will do, before doing it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <thread>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/run/simd_choice.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/run/wall_time_estimate.hpp"
#include "engine/spec/work_bound.hpp"
#include "engine/tune/tune_spec.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

std::string preview(const Axis& axis) {
  if (axis.kind == "repeat") return "each run's seed = splitmix64(master seed, run_id)";
  std::string s;
  const std::size_t n = axis.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (n > 8 && i == 3) {
      s += ", ...";
      i = n - 3;
    }
    std::string v;
    axis.visit(i, [&](const std::string& key, const SpecValue& value) {
      if (!v.empty()) v += ' ';
      if (axis.kind != "axis") v.append(key).append("=");
      v += to_text(value);
    });
    if (!s.empty()) s += ", ";
    if (axis.kind == "axis") s += v;
    else s.append("{").append(v).append("}");
  }
  return s;
}

// "  (7 x 3 x 8)": the sizes of a product's axes ("" when it has none).
std::string shape_of(const std::vector<Axis>& own, const std::vector<Axis>& shared) {
  std::string shape;
  for (const auto* axes : {&own, &shared})
    for (const Axis& a : *axes) shape += (shape.empty() ? "" : " x ") + std::to_string(a.size());
  return shape.empty() ? "" : "  (" + shape + ")";
}

void print_axes(const std::vector<Axis>& axes, const std::string& indent) {
  for (const Axis& a : axes) std::cout << indent << a.name() << ": " << a.size() << " values: " << preview(a) << "\n";
}

// ns per lane-step of this machine's kernels on (up to) 16 of the spec's own
// runs, each cut to 2000 steps.
double calibrate(const SweepSpec& spec, EnvironmentCache& cache, SimdTarget target) {
  std::vector<RunTuple> tuples;
  const std::int64_t n = std::min<std::int64_t>(16, spec.size());
  for (std::int64_t k = 0; k < n; ++k) {
    RunTuple t = resolve_run(k * spec.size() / n, spec.run(k * spec.size() / n), cache);
    t.params.max_time = 2000 * t.params.f * t.params.dt;
    tuples.push_back(t);
  }
  const ThreadBatchEvaluator lanes(1, target);
  std::vector<RunResult> results(tuples.size());
  const auto t0 = std::chrono::steady_clock::now();
  lanes.evaluate(tuples, results);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double steps = 0;
  for (const RunResult& r : results) steps += double(r.steps + r.transit_points);
  return steps > 0 ? 1e9 * s / steps : NAN;
}

struct EstimateFlags {
  bool on = false;
  int threads = 0;
  std::int64_t runs = 1024;
};

std::string duration_text(double s) {
  char buf[64];
  if (s < 120) std::snprintf(buf, sizeof buf, "%.3g s", s);
  else if (s < 7200) std::snprintf(buf, sizeof buf, "%.3g min", s / 60);
  else std::snprintf(buf, sizeof buf, "%.3g h", s / 3600);
  return buf;
}

void print_estimate(const SweepSpec& spec, EnvironmentCache& cache, SimdTarget target, const EstimateFlags& o) {
  const int threads = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  const WallTimeEstimate e = estimate_wall_time(spec, cache, ThreadBatchEvaluator(threads, target), o.runs);
  std::cout << "estimate    " << duration_text(e.seconds) << " wall on " << threads << " threads";
  if (e.runs_drawn == spec.size()) {
    std::cout << " (every run was run: the time of the calibration itself)\n";
    return;
  }
  std::cout << " (~95% interval " << duration_text(e.low) << " to " << duration_text(e.high) << "), from "
            << e.runs_drawn << " runs drawn across the spec that took " << duration_text(e.sample_seconds) << " here\n"
            << "            (the interval is the sampling error of the runs' work; the sample's last runs leave\n"
            << "            lanes idle, so it errs long, the more the fewer runs; a shared machine moves it)\n";
}

// A spec with [tune]: its cases, what each races, and the most runs the
// tune may take (every race spending its budget, then the validation runs).
void print_tune_plan(const SweepSpec& spec, const TuneSpec& tune, const WorkBound& work, double ns, SimdTarget target) {
  std::int64_t most = 0, most_per_case = 0;
  for (const TuneCase& c : tune.cases) {
    const std::int64_t n = c.budget + tune.validation_seeds;
    most += n;
    most_per_case = std::max(most_per_case, n);
  }
  std::cout << "tune '" << spec.name << "'" << (spec.description.empty() ? "" : ": " + spec.description) << "\n";
  std::cout << "runs        at most " << most << " (" << tune.cases.size()
            << " cases raced on their own; each its race budget + " << tune.validation_seeds
            << " validation runs, twice that with --grid)\n";
  std::cout << "race        " << to_string(tune.test) << " test at confidence " << format_number(tune.confidence)
            << ", first after " << tune.first_test << " seeds, then every " << tune.each_test << "; tune.seed "
            << tune.seed << "\n";
  std::cout << "cases       (label: parameters searched, race budget)\n";
  for (const TuneCase& c : tune.cases) {
    std::string p;
    for (std::size_t j : c.parameters) {
      const TuneParameter& q = tune.parameters[j];
      std::string domain;
      if (q.real) {
        domain = "[" + format_number(q.lo) + ", " + format_number(q.hi) + "]";
      } else {
        for (const SpecValue& v : q.choices) domain += (domain.empty() ? "{" : ", ") + to_text(v);
        domain += "}";
      }
      p += (p.empty() ? "" : ", ") + q.key + " in " + domain;
    }
    std::cout << "  " << (c.run.label.empty() ? "(no label)" : c.run.label) << ": "
              << (p.empty() ? "nothing (validated as given)" : p + ", " + std::to_string(c.budget) + " runs") << "\n";
  }
  // The spec's bound is over its cases, one run each: a case runs at most most_per_case times.
  const double steps = work.steps * double(most_per_case);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "work        at most %s%.3g integration steps (every run to its time budget; most end sooner)\n"
                "            %.1f ns per lane-step measured here (%s kernels) -> at most %.3g core-hours\n",
                work.sampled ? "about " : "", steps, ns, to_string(target), steps * ns * 1e-9 / 3600);
  std::cout << buf;
}

}  // namespace

void add_plan_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("plan", "Show what a sweep spec expands to and bound its work, without running it");
  auto spec_path = std::make_shared<std::string>();
  auto sets = std::make_shared<std::vector<std::string>>();
  auto est = std::make_shared<EstimateFlags>();
  cmd->add_option("spec", *spec_path, "sweep spec (TOML)")->required()->check(CLI::ExistingFile);
  add_set_option(*cmd, *sets);
  cmd->add_flag("--estimate", est->on,
                "also run calibration runs drawn across the spec and estimate the sweep's wall time");
  cmd->add_option("--threads", est->threads, "threads the sweep will use, for --estimate (default: all cores)")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--calibration", est->runs,
                  "calibration runs for --estimate (default 1024; more narrow the interval and the overestimate a "
                  "small sample makes)")
      ->check(CLI::Range(1, 100000));
  cmd->callback([spec_path, sets, est, &action] {
    action = [spec_path, sets, est]() -> int {
      SweepSpec spec;
      EnvironmentCache cache;
      SimdTarget target;
      WorkBound work;
      TuneSpec tune;
      try {
        target = selected_simd_target();
        spec = load_sweep_spec(*spec_path, spec_overrides(*sets));
        if (!spec.tune.empty()) tune = tune_spec_of(spec, *spec_path);
        preload_environments(spec, cache);  // every map, named where the spec sets it, as sweep does
        work = bound_work(spec, cache);
      } catch (const std::exception& e) {
        std::cerr << "chaosweep plan: " << e.what() << "\n";
        return exit_bad_input;
      }
      if (!spec.tune.empty()) {
        print_tune_plan(spec, tune, work, calibrate(spec, cache, target), target);
        return exit_ok;
      }
      std::cout << "sweep '" << spec.name << "'" << (spec.description.empty() ? "" : ": " + spec.description) << "\n";
      if (!sets->empty()) {
        std::cout << "--set      ";
        for (const std::string& v : *sets) std::cout << " " << v;
        std::cout << "  (applied to the spec's text, which the sweep stores)\n";
      }
      if (spec.parts.empty()) {
        std::cout << "runs        " << spec.size() << shape_of(spec.axes, {}) << "\n";
        std::cout << "axes        (first varies slowest)\n";
        print_axes(spec.axes, "  ");
      } else {
        std::cout << "runs        " << spec.size() << " in " << spec.parts.size() << " parts, one after the other\n";
        std::cout << "parts       (each: its fixed settings, then its axes, first slowest"
                  << (spec.axes.empty() ? "" : ", then the shared axes") << ")\n";
        for (std::size_t k = 0; k < spec.parts.size(); ++k) {
          const SpecPart& part = spec.parts[k];
          const std::int64_t first = spec.part_offset(k), n = spec.part_size(k);
          std::cout << "  part \"" << part.name << "\": " << n << " runs" << shape_of(part.axes, spec.axes)
                    << ", run_id " << first << "-" << first + n - 1 << "\n";
          if (!part.fixed.empty()) {
            std::string f;
            for (const auto& [key, value] : part.fixed) f += (f.empty() ? "" : " ") + key + "=" + to_text(value);
            std::cout << "    fixed: " << f << "\n";
          }
          print_axes(part.axes, "    ");
        }
        if (!spec.axes.empty()) {
          std::cout << "axes        shared by every part, after its own (first varies slowest)\n";
          print_axes(spec.axes, "  ");
        }
      }
      const RunSpec first = spec.run(0);
      std::cout << "first run   env " << first.env << ", " << format_number(first.params.size_x) << " x "
                << format_number(first.params.size_y) << " m, sr " << format_number(first.params.sr) << " m, planner "
                << to_string(first.params.planner) << ", variant " << variant_name(first.params) << "\n";
      char buf[256];
      const double ns = calibrate(spec, cache, target);
      std::snprintf(buf, sizeof buf,
                    "work        at most %s%.3g integration steps (every run to its time budget; most end sooner)\n"
                    "            %.1f ns per lane-step measured here (%s kernels) -> at most %.3g core-hours\n",
                    work.sampled ? "about " : "", work.steps, ns, to_string(target), work.steps * ns * 1e-9 / 3600);
      std::cout << buf;
      if (work.sampled)
        std::cout << "            (estimated from " << work.evaluated
                  << " runs drawn at random: the axes that set time budgets have too many combinations to walk)\n";
      if (est->on) print_estimate(spec, cache, target, *est);
      return exit_ok;
    };
  });
}

}  // namespace chaosweep
