#include "apps/chaosweep/slurm_values.hpp"

#include <cctype>
#include <cstdio>
#include <regex>

namespace chaosweep {

namespace {

// Long enough for any real value, short enough to keep a script readable.
constexpr std::size_t max_length = 200;

// "'VALUE' WHAT" (built by appending: GCC 12 warns, wrongly, on "'" + string&&).
std::string refused(const std::string& value, const std::string& what) {
  std::string m = "'";
  m += printable(value);
  m += "' ";
  m += what;
  return m;
}

bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; }

std::optional<std::string> check_name(const std::string& value, const char* what, bool list) {
  const std::string form = std::string("must be ") + (list ? "one or more names separated by ','" : "a name") +
                           " of letters, digits, '_', '-' and '.' (at most " + std::to_string(max_length) +
                           " characters)";
  bool ok = !value.empty() && value.size() <= max_length;
  bool at_start = true;
  for (char c : value) {
    if (list && c == ',' && !at_start) {
      at_start = true;
    } else if (name_char(c)) {
      at_start = false;
    } else {
      ok = false;
    }
  }
  if (ok && !at_start) return std::nullopt;
  return refused(value, std::string("is not a SLURM ") + what + ": it " + form);
}

}  // namespace

std::optional<std::string> check_slurm_partition(const std::string& value) {
  return check_name(value, "partition", true);
}
std::optional<std::string> check_slurm_account(const std::string& value) { return check_name(value, "account", false); }
std::optional<std::string> check_slurm_job_name(const std::string& value) {
  return check_name(value, "job name", false);
}

std::optional<std::string> check_slurm_time(const std::string& value) {
  static const std::regex form(
      R"((\d{1,7}(:\d{1,2}){0,2})|(\d{1,5}-\d{1,2}(:\d{1,2}){0,2})|UNLIMITED|INFINITE|unlimited|infinite)");
  if (value.size() <= 32 && std::regex_match(value, form)) return std::nullopt;
  return refused(value,
                 "is not a SLURM time: give MINUTES, MINUTES:SECONDS, HOURS:MINUTES:SECONDS, DAYS-HOURS, "
                 "DAYS-HOURS:MINUTES, DAYS-HOURS:MINUTES:SECONDS (digits, e.g. 02:00:00 or 1-12) or UNLIMITED");
}

std::optional<std::string> check_slurm_mem(const std::string& value) {
  static const std::regex form(R"(\d{1,12}[KMGTkmgt]?)");
  if (std::regex_match(value, form)) return std::nullopt;
  return refused(value,
                 "is not a SLURM memory size: give a whole number with an optional unit K, M, G or T (e.g. "
                 "4G; no unit: megabytes)");
}

std::optional<std::string> check_slurm_directive_path(const std::string& value) {
  for (unsigned char c : value)
    if (c < 0x20 || c == 0x7f || c == ' ' || c == '"' || c == '\'' || c == '\\' || c == '#' || c == '%')
      return refused(value,
                     "cannot be written into an #SBATCH line (the job's log path): it must not hold white space, "
                     "control characters, quotes, '\\', '#' or '%'");
  return std::nullopt;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string printable(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += char(c);
    }
  }
  return out;
}

std::string to_slurm_job_name(const std::string& s) {
  std::string out;
  for (char c : s.substr(0, max_length)) out += name_char(c) ? c : '_';
  return out.empty() ? std::string("sweep") : out;
}

}  // namespace chaosweep
