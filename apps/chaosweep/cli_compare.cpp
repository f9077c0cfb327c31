// `chaosweep compare A.h5 B.h5`
#include <iostream>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/store/h5_compare.hpp"

namespace chaosweep {

void add_compare_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("compare", "Compare two result files run by run and in distribution");
  cmd->footer(
      "Aligns runs on run_id when both files come from the same spec, on their parameters\n"
      "(param_hash) otherwise; compares every output column (floats within --atol + --rtol*|B|),\n"
      "lists changed, missing and extra runs, and per group (variant, env, size, SR) compares\n"
      "the coverage times of ok runs with a Mann-Whitney U test. Exit 0 when every aligned run\n"
      "agrees and none is missing or extra, 1 otherwise (like diff), 2 for bad input.");
  auto a = std::make_shared<std::string>(), b = std::make_shared<std::string>();
  auto opt = std::make_shared<CompareOptions>();
  cmd->add_option("a", *a, "result file A")->required()->check(CLI::ExistingFile);
  cmd->add_option("b", *b, "result file B")->required()->check(CLI::ExistingFile);
  cmd->add_option("--rtol", opt->rtol, "relative tolerance for float columns")
      ->check(not_nan())
      ->check(CLI::Range(0.0, 1e9));
  cmd->add_option("--atol", opt->atol, "absolute tolerance for float columns")
      ->check(not_nan())
      ->check(CLI::Range(0.0, 1e300));
  cmd->add_option("--show", opt->show, "differences to list")->check(CLI::Range(0, 1000000));
  cmd->callback([a, b, opt, &action] {
    action = [a, b, opt]() -> int {
      try {
        const CompareReport r = compare_results(*a, *b, *opt);
        std::cout << r.text();
        return r.same() ? exit_ok : 1;
      } catch (const std::exception& e) {
        std::cerr << "chaosweep compare: " << e.what() << "\n";
        return exit_bad_input;
      }
    };
  });
}

}  // namespace chaosweep
