#pragma once
// Values that `chaosweep slurm` writes into a job script. A script is run by a
// shell and its #SBATCH lines are read by sbatch, so a value copied as given
// could add a command (a newline, `;`, `$(...)`). Each value is therefore
// checked against the form SLURM accepts for it, and free text (paths) is
// shell-quoted.
#include <optional>
#include <string>

namespace chaosweep {

// Each check returns nullopt when `value` is acceptable, else what is wrong
// and the allowed form (the caller names the flag).
std::optional<std::string> check_slurm_partition(const std::string& value);  // name[,name...]
std::optional<std::string> check_slurm_account(const std::string& value);
std::optional<std::string> check_slurm_job_name(const std::string& value);
// MINUTES, MINUTES:SECONDS, HOURS:MINUTES:SECONDS, DAYS-HOURS, DAYS-HOURS:MINUTES,
// DAYS-HOURS:MINUTES:SECONDS, or UNLIMITED / INFINITE (sbatch --time).
std::optional<std::string> check_slurm_time(const std::string& value);
// A whole number with an optional unit K, M, G or T (sbatch --mem).
std::optional<std::string> check_slurm_mem(const std::string& value);
// A path written into #SBATCH --output: sbatch splits such lines at white
// space, reads quotes, backslashes and '#' and expands '%' patterns, so none
// of those (nor control characters) may occur in it.
std::optional<std::string> check_slurm_directive_path(const std::string& value);

// `s` as one shell word in single quotes ('it'\''s').
std::string shell_quote(const std::string& s);
// `s` for a message on one line: control characters as \n, \t, \xNN.
std::string printable(const std::string& s);
// A job name made from free text (a spec's name): every character a job name
// may not hold becomes '_'.
std::string to_slurm_job_name(const std::string& s);

}  // namespace chaosweep
