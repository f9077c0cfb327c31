#pragma once
// Helpers shared by the subcommands: run-parameter flags generated from the
// parameter table, exit codes, provenance.
#include <CLI/CLI.hpp>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

#include "run_params.hpp"
#include "sweep_spec.hpp"

namespace chaosweep {

// Exit codes: 0 success (a run that ended timeout/stuck/diverged still ran),
// 2 bad input (usage, out-of-range value, invalid run), 3 I/O or internal error.
inline constexpr int exit_ok = 0, exit_bad_input = 2, exit_failure = 3;

// Adds --<param> for every parameter of the table plus --size, --start, --ic
// and --env; raw values land in `raw` keyed by setting name.
void add_param_flags(CLI::App& app, std::map<std::string, std::string>& raw);

// Applies raw flag values; throws SpecError naming the flag.
void apply_param_flags(const std::map<std::string, std::string>& raw, RunSpec& run);

// An output file that exists and may not be replaced (bad input: exit 2).
struct OutputExists : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A CLI11 check that a value is a number and not NaN (CLI::Range lets NaN
// through: every comparison with it is false). Put it before the Range.
const CLI::Validator& not_nan();

// Adds --force to a command that writes files: results can be hours of work,
// so no command replaces an existing file unless asked to.
void add_force_flag(CLI::App& cmd, bool& force);

// Throws OutputExists naming `path` (and `flag`, the option that gave it)
// when the file exists and `force` is not set; `more` ends the message.
void check_output_free(const std::string& path, bool force, const std::string& flag = "-o",
                       const std::string& more = "");

// Runs a subcommand's body: BadInput (the module's error for bad input) and
// OutputExists become a message and exit 2, any other exception a message
// and exit 3.
template <class BadInput, class Body>
int run_reporting(const char* command, Body&& body) {
  try {
    return body();
  } catch (const OutputExists& e) {
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

std::string host_name();
std::string utc_now();  // ISO 8601

}  // namespace chaosweep
