#include "apps/chaosweep/sweep/sweep_flags.hpp"

#include "apps/chaosweep/cli_common.hpp"

namespace chaosweep {

void add_sweep_flags(CLI::App& cmd, SweepFlags& o) {
  cmd.add_option("spec", o.spec, "sweep spec (TOML)")->required()->check(CLI::ExistingFile);
  add_set_option(cmd, o.sets);
  cmd.add_option("-o,--output", o.out, "result file (HDF5)")->required();
  cmd.add_option("--threads", o.threads, "worker threads (0: all cores)")
      ->check(CLI::Number)
      ->check(CLI::Range(0, 4096));
  cmd.add_option("--shard", o.shard,
                 "run only shard K of N (run_ids i with i % N == K); default: from SLURM_ARRAY_TASK_ID "
                 "and SLURM_ARRAY_TASK_COUNT when set")
      ->type_name("K/N");
  cmd.add_flag("--resume", o.resume,
               "continue OUT.partial of the same spec, environment files and shard (or do nothing if OUT is "
               "complete)");
  cmd.add_flag("--force", o.force,
               "run even though OUT (replaced when this sweep completes) or OUT.partial (started over) exists");
  cmd.add_option("--batch", o.batch, "runs per write to OUT.partial")
      ->check(CLI::Number)
      ->check(CLI::Range(1, 1 << 24));
  cmd.add_option("--flush-seconds", o.flush_seconds,
                 "also write the finished runs to OUT.partial once this many seconds passed since the last write "
                 "(0: only every --batch runs)")
      ->check(not_nan())
      ->check(CLI::Range(0.0, 1e6))
      ->default_str("10");
  cmd.add_flag("-q,--quiet", o.quiet, "print nothing but errors (and progress only with --progress=always)");
  cmd.add_option("--progress", o.progress,
                 "progress on stderr: a live line on a terminal, a plain line every 30 s otherwise")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->default_str("auto");
}

}  // namespace chaosweep
