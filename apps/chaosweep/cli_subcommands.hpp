#pragma once
// Each subcommand registers itself on the app and, when chosen, sets the
// action main() runs after parsing.
#include <CLI/CLI.hpp>
#include <functional>

namespace chaosweep {
void add_run_command(CLI::App& app, std::function<int()>& action);
void add_sweep_command(CLI::App& app, std::function<int()>& action);
void add_tune_command(CLI::App& app, std::function<int()>& action);
void add_plan_command(CLI::App& app, std::function<int()>& action);
void add_merge_command(CLI::App& app, std::function<int()>& action);
void add_compare_command(CLI::App& app, std::function<int()>& action);
void add_slurm_commands(CLI::App& app, std::function<int()>& action);
// `chaosweep status` (cli_status.cpp); added by add_slurm_commands.
void add_status_command(CLI::App& app, std::function<int()>& action);
void add_log_command(CLI::App& app, std::function<int()>& action);
void add_export_command(CLI::App& app, std::function<int()>& action);
void add_bench_command(CLI::App& app, std::function<int()>& action);
void add_table_command(CLI::App& app, std::function<int()>& action);
void add_figure_command(CLI::App& app, std::function<int()>& action);
}  // namespace chaosweep
