#include "engine/bench/variants.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/spec/run_tuple.hpp"
#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

namespace {

using clock_type = std::chrono::steady_clock;

struct Variant {
  const char* name;
  const char* fixed;  // TOML keys of the [fixed] table
};

// Table 1's technique sets with the defaults of docs/spec.md §2 (c = 0.25)
// and f = 2 for scaling (f = 1 is no scaling).
const Variant variants[] = {
    {"original", ""},
    {"IS", "index_switching = 1\n"},
    {"SC", "f = 2\n"},
    {"MZ", "map_zoning = 1\n"},
    {"IS+MZ+SC", "index_switching = 1\nmap_zoning = 1\nf = 2\n"},
    {"logistic", "planner = \"logistic\"\nlogistic_jitter = 1e-6\n"},
};

struct MapCase {
  double size, sr;
  const char* env;  // the label
  const char* spec_env;
};
const MapCase maps[] = {
    {50, 1, "open", "empty"},  {50, 1, "five_squares", "five_squares"},
    {50, 4, "open", "empty"},  {50, 4, "five_squares", "five_squares"},
    {200, 1, "open", "empty"}, {200, 1, "five_squares", "five_squares"},
    {200, 4, "open", "empty"}, {200, 4, "five_squares", "five_squares"},
};

// One cell's runs: the first `runs` of seeds x ds_index 1-3 (ic jittered
// by 1e-6 per seed, as table1_search.toml), so every cell runs the same
// parameters but its map and technique set.
std::vector<RunTuple> cell_runs(const MapCase& m, const Variant& v, const VariantOptions& o) {
  char head[512];
  std::snprintf(
      head, sizeof head,
      "[fixed]\nsize = %g\nsr = %g\nenv = \"%s\"\ndc = 0.9\nmax_pr = 50\nmax_time = %.17g\nic_jitter = 1e-6\n", m.size,
      m.sr, m.spec_env, o.max_time);
  const int seeds = (o.runs + 2) / 3;
  const std::string text = std::string(head) + v.fixed +
                           "[axes]\nseed = { start = 0, stop = " + std::to_string(seeds - 1) +
                           ", step = 1 }\nds_index = [1, 2, 3]\n";
  const SweepSpec spec = parse_sweep_spec(text, "bench --variants");
  EnvironmentCache cache;
  std::vector<RunTuple> tuples;
  for (std::int64_t i = 0; i < o.runs; ++i) tuples.push_back(resolve_run(i, spec.run(i), cache));
  return tuples;
}

}  // namespace

const std::vector<std::string>& bench_variant_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Variant& v : variants) n.push_back(v.name);
    return n;
  }();
  return names;
}

VariantsReport run_variants_bench(const VariantOptions& o) {
  VariantsReport r;
  r.options = o;
  const SimdTarget target = best_simd_target();
  r.target = to_string(target);
  const ThreadBatchEvaluator lanes(1, target);
  const auto t_all = clock_type::now();
  {
    // Untimed warm-up (first-touch of the code, the environment files), so
    // that the first cell, the ratios' base, is not charged for it.
    VariantOptions w = o;
    w.runs = std::min(o.runs, 8);
    const std::vector<RunTuple> tuples = cell_runs(maps[0], variants[0], w);
    std::vector<RunResult> results(tuples.size());
    lanes.evaluate(tuples, results);
  }
  // The cells in report order (map, then variant), their runs resolved once.
  std::vector<std::vector<RunTuple>> runs;
  for (const MapCase& m : maps)
    for (const Variant& v : variants) {
      runs.push_back(cell_runs(m, v, o));
      VariantCell c;
      c.size = m.size, c.sr = m.sr, c.env = m.env, c.variant = v.name, c.runs = o.runs;
      r.cells.push_back(c);
    }
  // Each cell's base: original on the open map of the same size and SR.
  std::vector<std::size_t> base(r.cells.size());
  for (std::size_t i = 0; i < r.cells.size(); ++i)
    for (std::size_t b = 0; b < r.cells.size(); ++b)
      if (r.cells[b].size == r.cells[i].size && r.cells[b].sr == r.cells[i].sr && r.cells[b].env == "open" &&
          r.cells[b].variant == "original")
        base[i] = b;
  // A block: the cells sharing a base (both maps of one size and SR).
  std::vector<std::vector<std::size_t>> blocks;
  for (std::size_t i = 0; i < r.cells.size(); ++i) {
    auto it = std::find_if(blocks.begin(), blocks.end(), [&](const auto& bl) { return base[bl.front()] == base[i]; });
    if (it == blocks.end()) blocks.push_back({i});
    else it->push_back(i);
  }
  const auto ns_per_step = [](const VariantCell& c, double seconds) {
    return 1e9 * seconds / (c.arnold_steps + c.transit_points);
  };
  std::vector<std::vector<double>> ratios(r.cells.size());
  for (int round = 0; round < o.rounds; ++round)
    for (const std::vector<std::size_t>& bl : blocks) {
      for (std::size_t k = 0; k < bl.size(); ++k) {
        const std::size_t i = bl[(k + std::size_t(round)) % bl.size()];
        std::vector<RunResult> results(runs[i].size());
        const auto t0 = clock_type::now();
        lanes.evaluate(runs[i], results);
        VariantCell& c = r.cells[i];
        c.round_seconds.push_back(std::chrono::duration<double>(clock_type::now() - t0).count());
        if (round == 0)
          for (const RunResult& x : results) {  // the same every round: a run is a pure function of its parameters
            c.arnold_steps += double(x.steps);
            c.transit_points += double(x.transit_points);
          }
      }
      for (std::size_t i : bl) {
        const VariantCell &c = r.cells[i], &b = r.cells[base[i]];
        ratios[i].push_back(ns_per_step(c, c.round_seconds.back()) / ns_per_step(b, b.round_seconds.back()));
      }
    }
  r.seconds = std::chrono::duration<double>(clock_type::now() - t_all).count();
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  for (std::size_t i = 0; i < r.cells.size(); ++i) {
    VariantCell& c = r.cells[i];
    c.seconds = median(c.round_seconds);
    c.ns_per_step = ns_per_step(c, c.seconds);
    c.ratio = median(ratios[i]);
    c.ratio_min = *std::min_element(ratios[i].begin(), ratios[i].end());
    c.ratio_max = *std::max_element(ratios[i].begin(), ratios[i].end());
  }
  return r;
}

std::string variants_json(const VariantsReport& r) {
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "{\n  \"runs_per_cell\": %d,\n  \"rounds\": %d,\n  \"max_time\": %.17g,\n  \"threads\": 1,\n  "
                "\"target\": \"%s\",\n"
                "  \"step\": \"Arnold steps (Logistic points for logistic) + transit points\",\n"
                "  \"seconds\": %.3f,\n  \"cells\": [",
                r.options.runs, r.options.rounds, r.options.max_time, r.target.c_str(), r.seconds);
  std::string s = buf;
  for (std::size_t i = 0; i < r.cells.size(); ++i) {
    const VariantCell& c = r.cells[i];
    std::snprintf(buf, sizeof buf,
                  "%s\n    {\"size\": %g, \"sr\": %g, \"env\": \"%s\", \"variant\": \"%s\", \"runs\": %d, "
                  "\"arnold_steps\": %.0f, \"transit_points\": %.0f, \"seconds\": %.6f, \"ns_per_step\": %.4f, "
                  "\"ratio\": %.4f, \"ratio_min\": %.4f, \"ratio_max\": %.4f}",
                  i ? "," : "", c.size, c.sr, c.env.c_str(), c.variant.c_str(), c.runs, c.arnold_steps,
                  c.transit_points, c.seconds, c.ns_per_step, c.ratio, c.ratio_min, c.ratio_max);
    s += buf;
  }
  return s + "\n  ]\n}";
}

std::string variants_text(const VariantsReport& r) {
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "technique variants, 1 thread (%s lanes), %d runs per cell, dc 0.9, max_pr 50, max_time %g s;\n"
                "ns per simulated step = wall time (setup included) / (Arnold steps, or Logistic points, + transit "
                "points),\nthe median of %d rounds (a map size and SR's cells back to back, in turn);\n"
                "(x) = ratio to original on the open map of the same size and SR, the median of the rounds' ratios%s;\n"
                "measured in %.1f s\n\n",
                r.target.c_str(), r.options.runs, r.options.max_time, r.options.rounds,
                r.options.rounds > 1 ? " (x, least-greatest)" : "", r.seconds);
  std::string s = buf;
  s += "| map | ";
  for (const std::string& n : bench_variant_names()) s += n + " | ";
  s += "transit share |\n|---|";
  for (std::size_t k = 0; k <= bench_variant_names().size(); ++k) s += "---|";
  s += "\n";
  const std::size_t nv = bench_variant_names().size();
  for (std::size_t row = 0; row + nv <= r.cells.size(); row += nv) {
    const VariantCell& f = r.cells[row];
    std::snprintf(buf, sizeof buf, "| %g m SR %g %s | ", f.size, f.sr, f.env.c_str());
    s += buf;
    double transit = 0, steps = 0;
    for (std::size_t k = 0; k < nv; ++k) {
      const VariantCell& c = r.cells[row + k];
      if (r.options.rounds > 1)
        std::snprintf(buf, sizeof buf, "%.1f (%.2fx, %.2f-%.2f) | ", c.ns_per_step, c.ratio, c.ratio_min, c.ratio_max);
      else std::snprintf(buf, sizeof buf, "%.1f (%.2fx) | ", c.ns_per_step, c.ratio);
      s += buf;
      transit += c.transit_points;
      steps += c.arnold_steps + c.transit_points;
    }
    std::snprintf(buf, sizeof buf, "%.1f%% |\n", 100 * transit / steps);
    s += buf;
  }
  return s;
}

}  // namespace chaosweep
