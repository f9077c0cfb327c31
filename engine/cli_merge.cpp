// `chaosweep merge -o OUT.h5 SHARDS...`
#include <iostream>

#include "cli_common.hpp"
#include "cli_subcommands.hpp"
#include "h5_merge.hpp"
#include "slurm_dir.hpp"

namespace chaosweep {

void add_merge_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("merge", "Merge the shard files of one sweep into one result file");
  cmd->footer(
      "Checks that every input comes from the same spec (spec_hash), the same environment files\n"
      "(inputs_hash; a differing file is named) and shard count, reports missing and duplicated\n"
      "run_ids and which shards to re-run, and only when none is missing\n"
      "or duplicated writes OUT with the rows sorted by run_id. Exit 0 merged, 1 incomplete,\n"
      "2 bad input. Example: chaosweep merge -o out/fig6.h5 out/fig6.shard*.h5\n"
      "--slurm-dir DIR takes the shards of a `chaosweep slurm` directory (DIR/shard_K.h5 for each\n"
      "task of DIR/cluster.toml) instead of a list, which for many tasks would not fit on a\n"
      "command line.");
  auto out = std::make_shared<std::string>();
  auto inputs = std::make_shared<std::vector<std::string>>();
  auto slurm_dir = std::make_shared<std::string>();
  auto force = std::make_shared<bool>(false);
  cmd->add_option("-o,--output", *out, "merged result file")->required();
  auto* shards = cmd->add_option("shards", *inputs, "shard result files")->check(CLI::ExistingFile);
  cmd->add_option("--slurm-dir", *slurm_dir, "the shards of this `chaosweep slurm` directory")
      ->check(CLI::ExistingDirectory)
      ->excludes(shards);
  add_force_flag(*cmd, *force);
  cmd->callback([out, inputs, slurm_dir, force, &action] {
    action = [out, inputs, slurm_dir, force]() -> int {
      try {
        if (!slurm_dir->empty()) {
          *inputs = existing_shard_files(*slurm_dir);
          if (inputs->empty()) throw std::runtime_error("--slurm-dir: " + *slurm_dir + " holds no shard file yet");
        } else if (inputs->empty()) {
          throw std::runtime_error("give the shard files, or --slurm-dir DIR");
        }
        check_output_free(*out, *force);
        const MergeReport r = merge_results(*inputs, *out);
        std::cout << r.text() << "\n";
        if (!r.ok()) {
          std::cerr << "chaosweep merge: incomplete, nothing written\n";
          return 1;
        }
        std::cout << "merged -> " << *out << "\n";
        return exit_ok;
      } catch (const std::exception& e) {
        std::cerr << "chaosweep merge: " << e.what() << "\n";
        return exit_bad_input;
      }
    };
  });
}

}  // namespace chaosweep
