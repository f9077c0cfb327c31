#pragma once
// Helpers shared by the subcommands: run-parameter flags generated from the
// parameter table, exit codes, provenance.
#include <CLI/CLI.hpp>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/run/progress.hpp"
#include "engine/spec/spec_overrides.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "engine/store/provenance.hpp"
#include "kernels/core/run_params.hpp"

namespace chaosweep {

// Exit codes: 0 success (a run that ended timeout/stuck/diverged still ran),
// 2 bad input (usage, out-of-range value, invalid run), 3 I/O or internal error;
// 1 (like diff) when `run --from`, `compare` or `merge` found a difference.
inline constexpr int exit_ok = 0, exit_differs = 1, exit_bad_input = 2, exit_failure = 3;

// Adds --<param> for every parameter of the table plus --size, --start, --ic
// and --env; raw values land in `raw` keyed by setting name.
void add_param_flags(CLI::App& app, std::map<std::string, std::string>& raw);

// Applies raw flag values; throws SpecError naming the flag.
void apply_param_flags(const std::map<std::string, std::string>& raw, RunSpec& run);

// An output path that cannot be used (bad input: exit 2): empty, a
// directory, or (OutputExists) a file that may not be replaced.
struct OutputPathError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct OutputExists : OutputPathError {
  using OutputPathError::OutputPathError;
};

// A CLI11 check that a value is a number and not NaN (CLI::Range lets NaN
// through: every comparison with it is false). Put it before the Range.
const CLI::Validator& not_nan();

// Adds --set KEY=VALUE (repeatable) to plan, sweep and slurm: a change of the
// spec's [fixed] settings or [axes] (engine/spec/spec_overrides.hpp).
void add_set_option(CLI::App& cmd, std::vector<std::string>& sets);
// The parsed --set values; throws SpecError naming a malformed one.
std::vector<SpecOverride> spec_overrides(const std::vector<std::string>& sets);

// Adds --force to a command that writes files: results can be hours of work,
// so no command replaces an existing file unless asked to.
void add_force_flag(CLI::App& cmd, bool& force);

// --progress auto|always|never as the reporter's mode; -q silences "auto".
ProgressMode progress_mode(const std::string& progress, bool quiet);

// Throws OutputPathError naming `path` and `flag` (the option that gave it)
// unless `path` can name an output file: not empty, not a directory, not
// ending in a directory separator. Checked before any work, so that a bad
// path is not found only when the finished file is moved into place.
void check_output_path(const std::string& path, const std::string& flag = "-o");

// Throws OutputExists naming `path` (and `flag`, the option that gave it)
// when the file exists and `force` is not set; `more` ends the message. A
// non-empty `path` must pass check_output_path (with or without `force`).
void check_output_free(const std::string& path, bool force, const std::string& flag = "-o",
                       const std::string& more = "");

// Runs a subcommand's body: BadInput (the module's error for bad input) and
// OutputPathError become a message and exit 2, any other exception a message
// and exit 3.
template <class BadInput, class Body>
int run_reporting(const char* command, Body&& body) {
  try {
    return body();
  } catch (const OutputPathError& e) {
    std::cerr << "chaosweep " << command << ": " << e.what() << "\n";
    return exit_bad_input;
  } catch (const BadInput& e) {
    std::cerr << "chaosweep " << command << ": " << e.what() << "\n";
    return exit_bad_input;
  } catch (const std::exception& e) {
    std::cerr << "chaosweep " << command << ": " << e.what() << "\n";
    return exit_failure;
  }
}

// "a, b or c": a list of names for a flag's one-line help.
std::string names_or(const std::vector<std::string>& names);

// The positionals of `table` and `figure`: `name` (one of `names`) and the
// result files (none for the names `needs_results` says are computed).
void add_name_and_results(CLI::App& cmd, std::string& name, std::vector<std::string>& files,
                          const std::vector<std::string>& names, bool (*needs_results)(const std::string&));

}  // namespace chaosweep
