// `chaosweep merge -o OUT.h5 SHARDS...`
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <iostream>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/store/disk_room.hpp"
#include "engine/store/h5_merge.hpp"
#include "engine/store/output_lock.hpp"
#include "engine/store/rollback_driver.hpp"
#include "engine/store/slurm_dir.hpp"

namespace chaosweep {

namespace {

// What a SIGINT/SIGTERM during a merge removes: the half-written merged file,
// its journal and our lock file (paths set before the handler is installed;
// unlink and _exit are async-signal-safe).
const char* volatile cleanup_paths[3] = {nullptr, nullptr, nullptr};

extern "C" void on_merge_signal(int sig) {
  for (const char* volatile p : cleanup_paths)
    if (p) unlink(p);
  _exit(128 + sig);
}

}  // namespace

void add_merge_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("merge", "Merge the shard files of one sweep into one result file");
  cmd->footer(
      "Checks that every input comes from the same spec (spec_hash), the same environment files\n"
      "(inputs_hash; a differing file is named) and shard count and is an intact shard (shard K\n"
      "of N holds run_ids K, K+N, ... in order), reports missing run_ids and which shards to\n"
      "re-run, and only when none is missing writes OUT with the rows sorted by run_id (via\n"
      "OUT.merging, renamed at the end; SIGINT/SIGTERM remove it). Holds OUT.lock like a sweep:\n"
      "refused while a sweep writes OUT, and refused without --force when an interrupted sweep's\n"
      "OUT.partial exists (kept either way). Exit 0 merged, 1 incomplete, 2 bad input.\n"
      "Example: chaosweep merge -o out/fig6.h5 out/fig6.shard*.h5\n"
      "--slurm-dir DIR takes the shards of a `chaosweep slurm` directory (DIR/shard_K.h5 for each\n"
      "task of DIR/cluster.toml) instead of a list, which for many tasks would not fit on a\n"
      "command line.");
  auto out = std::make_shared<std::string>();
  auto inputs = std::make_shared<std::vector<std::string>>();
  auto slurm_dir = std::make_shared<std::string>();
  auto force = std::make_shared<bool>(false);
  auto threads = std::make_shared<int>(0);
  cmd->add_option("-o,--output", *out, "merged result file")->required();
  auto* shards = cmd->add_option("shards", *inputs, "shard result files")->check(CLI::ExistingFile);
  cmd->add_option("--slurm-dir", *slurm_dir, "the shards of this `chaosweep slurm` directory")
      ->check(CLI::ExistingDirectory)
      ->excludes(shards);
  cmd->add_flag("--force", *force,
                "replace an existing OUT, and merge even though OUT.partial (an interrupted sweep) exists");
  cmd->add_option("--threads", *threads, "threads that unpack and compress the chunks (default: all cores)")
      ->check(CLI::Range(0, 4096));
  cmd->callback([out, inputs, slurm_dir, force, threads, &action] {
    action = [out, inputs, slurm_dir, force, threads]() -> int {
      static std::string temp, journal, lock_file;  // for the signal handler: alive to the end
      try {
        if (!slurm_dir->empty()) {
          *inputs = existing_shard_files(*slurm_dir);
          if (inputs->empty()) throw std::runtime_error("--slurm-dir: " + *slurm_dir + " holds no shard file yet");
        } else if (inputs->empty()) {
          throw std::runtime_error("give the shard files, or --slurm-dir DIR");
        }
        OutputLock lock(*out);  // a sweep writing OUT (or another merge) refuses us
        check_output_free(*out, *force);
        const std::string partial = *out + ".partial";
        if (!*force && std::filesystem::exists(partial))
          throw OutputExists("-o: " + partial + " exists (an interrupted sweep of " + *out +
                             "): continue it with sweep --resume, or pass --force to merge anyway (" + partial +
                             " is kept)");
        temp = merge_temp_path(*out);
        journal = journal_path(temp);
        lock_file = lock.path();
        cleanup_paths[0] = temp.c_str();
        cleanup_paths[1] = journal.c_str();
        cleanup_paths[2] = lock_file.c_str();
        std::signal(SIGINT, on_merge_signal);
        std::signal(SIGTERM, on_merge_signal);
        std::signal(SIGXFSZ, SIG_IGN);  // past ulimit -f a write fails (and is cleaned up), not the process
        const ThreadBatchEvaluator evaluator(*threads);
        MergeOptions options;
        options.parallel = [&](std::size_t n, const std::function<void(std::size_t)>& body) {
          evaluator.parallel(n, body);
        };
        const MergeReport r = merge_results(*inputs, *out, options);
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
        std::cout << r.text() << "\n";
        if (!r.ok()) {
          std::cerr << "chaosweep merge: incomplete, nothing written\n";
          return 1;
        }
        std::cout << "merged -> " << *out << "\n";
        return exit_ok;
      } catch (const OutOfRoom& e) {  // no room for it, or a write of it failed
        std::cerr << "chaosweep merge: " << e.what() << "; nothing written\n";
        return exit_failure;
      } catch (const std::exception& e) {
        std::cerr << "chaosweep merge: " << e.what() << "\n";
        return exit_bad_input;
      }
    };
  });
}

}  // namespace chaosweep
