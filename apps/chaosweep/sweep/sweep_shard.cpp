#include "apps/chaosweep/sweep/sweep_shard.hpp"

#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>

#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

namespace {

// A SLURM_ARRAY_* variable: unset, or a whole number in [0, 2^31) (anything
// else is refused naming it: a mistyped value must not run the whole sweep).
std::optional<int> slurm_number(const char* name) {
  const char* v = std::getenv(name);
  if (!v) return std::nullopt;
  const std::string text(v);
  if (!text.empty() && text.size() <= 10 && text.find_first_not_of("0123456789") == std::string::npos) {
    const long long n = std::stoll(text);
    if (n <= std::numeric_limits<int>::max()) return int(n);
  }
  throw SpecError(std::string(name) + " = '" + text +
                  "' is not a whole number in [0, 2147483647] (a SLURM job array sets it; pass --shard K/N to "
                  "choose the shard yourself)");
}

// The shard of a SLURM array task: (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN)
// / SLURM_ARRAY_TASK_STEP of SLURM_ARRAY_TASK_COUNT; no shard (the whole
// sweep) when neither the ID nor the COUNT is set.
Shard slurm_shard() {
  Shard s;
  const auto id = slurm_number("SLURM_ARRAY_TASK_ID"), count = slurm_number("SLURM_ARRAY_TASK_COUNT");
  const auto min = slurm_number("SLURM_ARRAY_TASK_MIN"), step = slurm_number("SLURM_ARRAY_TASK_STEP");
  if (!id && !count) return s;
  if (!id || !count)
    throw SpecError(std::string(id ? "SLURM_ARRAY_TASK_ID" : "SLURM_ARRAY_TASK_COUNT") + " is set but " +
                    (id ? "SLURM_ARRAY_TASK_COUNT" : "SLURM_ARRAY_TASK_ID") +
                    " is not: cannot tell this task's shard (pass --shard K/N)");
  const std::string vars = "SLURM_ARRAY_TASK_ID = " + std::to_string(*id) +
                           ", SLURM_ARRAY_TASK_MIN = " + std::to_string(min.value_or(0)) +
                           ", SLURM_ARRAY_TASK_STEP = " + std::to_string(step.value_or(1)) +
                           ", SLURM_ARRAY_TASK_COUNT = " + std::to_string(*count);
  const int offset = *id - min.value_or(0), stride = step.value_or(1);
  if (stride < 1 || offset < 0 || offset % stride != 0 || *count < 1 || offset / stride >= *count)
    throw SpecError(vars +
                    ": not a task of the array (need MIN <= ID, (ID - MIN) / STEP a whole number below "
                    "COUNT); pass --shard K/N");
  s.index = offset / stride;
  s.count = *count;
  return s;
}

}  // namespace

// "K/N", or the SLURM array task's shard (slurm_shard) when no --shard is given.
Shard parse_shard(const std::string& text) {
  if (text.empty()) return slurm_shard();
  Shard s;
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    std::size_t used = 0;
    s.index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument("");
    s.count = std::stoi(text.substr(slash + 1), &used);
    if (used != text.size() - slash - 1) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw SpecError("--shard: '" + text + "' is not K/N (e.g. 0/4)");
  }
  if (s.count < 1 || s.index < 0 || s.index >= s.count)
    throw SpecError("--shard: index " + std::to_string(s.index) + " of " + std::to_string(s.count) +
                    " is out of range: need 0 <= K < N");
  return s;
}

}  // namespace chaosweep
