// `chaosweep sweep`: expand a spec, run it on TBB, store rows in HDF5.
#include <unistd.h>

#include <cmath>
#include <iostream>
#include <thread>

#include "cli_common.hpp"
#include "cli_subcommands.hpp"
#include "h5_store.hpp"
#include "progress.hpp"
#include "simd_choice.hpp"
#include "sweep_runner.hpp"
#include "sweep_summary.hpp"
#include "version.hpp"

namespace chaosweep {

void add_sweep_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("sweep", "Run every run of a sweep spec and write the results to HDF5");
  cmd->footer(
      "The spec's axes are expanded as a Cartesian product (first axis slowest); each run is\n"
      "one row of /runs in OUT, in run_id order. Rows go to OUT.partial first; OUT appears only\n"
      "when the sweep completes. A failing run is recorded with its status, never aborts the\n"
      "sweep. Example: chaosweep sweep experiments/demo.toml -o out/demo/results.h5");
  struct Opts {
    std::string spec, out;
    int threads = 0;
    bool quiet = false;
    std::string progress = "auto";
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("spec", o->spec, "sweep spec (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->out, "result file (HDF5)")->required();
  cmd->add_option("--threads", o->threads, "worker threads (0: all cores)")->check(CLI::Range(0, 4096));
  cmd->add_flag("-q,--quiet", o->quiet, "print nothing but errors (and progress only with --progress=always)");
  cmd->add_option("--progress", o->progress,
                  "progress on stderr: a live line on a terminal, a plain line every 30 s otherwise")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->default_str("auto");
  cmd->callback([o, &action] {
    action = [o]() -> int {
      SweepSpec spec;
      SimdTarget target;
      try {
        target = selected_simd_target();
        spec = load_sweep_spec(o->spec);
        EnvironmentCache cache;
        preload_environments(spec, cache);
      } catch (const std::exception& e) {
        std::cerr << "chaosweep sweep: " << e.what() << "\n";
        return exit_bad_input;
      }
      const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
      const int threads = o->threads > 0 ? o->threads : int(cores);
      if (!o->quiet)
        std::cout << "sweep '" << spec.name << "': " << spec.size() << " runs on " << threads
                  << " threads, " << to_string(target) << " kernels -> " << o->out << "\n";
      SweepSummary summary;
      try {
        H5RunWriter writer(o->out);
        writer.set_attribute("engine_version", engine_version());
        writer.set_attribute("git_commit", git_commit());
        writer.set_attribute("git_dirty", git_dirty() ? "true" : "false");
        writer.set_attribute("spec", spec.text);
        writer.set_attribute("spec_path", o->spec);
        writer.set_attribute("spec_name", spec.name);
        writer.set_attribute("host", host_name());
        writer.set_attribute("threads", std::to_string(threads));
        writer.set_attribute("simd_target", to_string(target));
        writer.set_attribute("start_time", utc_now());
        SweepOptions opt;
        opt.threads = threads;
        opt.target = target;
        ProgressCounters counters;
        opt.progress = &counters;
        const ProgressMode mode = o->progress == "never" || (o->quiet && o->progress == "auto") ? ProgressMode::never
                                  : o->progress == "always"                                    ? ProgressMode::always
                                                                                               : ProgressMode::automatic;
        {
          ProgressReporter reporter(counters, spec.size(), mode);
          run_sweep(spec, opt, [&](const std::vector<RunRow>& rows) {
            writer.append(rows);
            for (const RunRow& r : rows) summary.add(r);
          });
        }
        writer.set_attribute("end_time", utc_now());
        writer.finish();
      } catch (const std::exception& e) {
        std::cerr << "chaosweep sweep: " << e.what() << "\n";
        return exit_failure;
      }
      if (!o->quiet) std::cout << summary.text() << "results     " << o->out << "\n";
      return exit_ok;
    };
  });
}

}  // namespace chaosweep
