// `chaosweep merge -o OUT.h5 SHARDS...`
#include <iostream>

#include "cli_common.hpp"
#include "cli_subcommands.hpp"
#include "h5_merge.hpp"

namespace chaosweep {

void add_merge_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("merge", "Merge the shard files of one sweep into one result file");
  cmd->footer(
      "Checks that every input comes from the same spec (spec_hash), the same environment files\n"
      "(inputs_hash; a differing file is named) and shard count, reports missing and duplicated\n"
      "run_ids and which shards to re-run, and only when none is missing\n"
      "or duplicated writes OUT with the rows sorted by run_id. Exit 0 merged, 1 incomplete,\n"
      "2 bad input. Example: chaosweep merge -o out/fig6.h5 out/fig6.shard*.h5");
  auto out = std::make_shared<std::string>();
  auto inputs = std::make_shared<std::vector<std::string>>();
  auto force = std::make_shared<bool>(false);
  cmd->add_option("-o,--output", *out, "merged result file")->required();
  cmd->add_option("shards", *inputs, "shard result files")->required()->check(CLI::ExistingFile);
  add_force_flag(*cmd, *force);
  cmd->callback([out, inputs, force, &action] {
    action = [out, inputs, force]() -> int {
      try {
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
