#pragma once
// A sweep spec (TOML): fixed parameters plus axes whose Cartesian product is
// the set of runs. run_id = index in the expansion, the first axis varying
// slowest, axes in file order. See experiments/README.md for the format.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "run_params.hpp"

namespace chaosweep {

struct SpecError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One value a key can take: a number, a name, or a tuple (start = [x, y]).
using SpecValue = std::variant<double, std::string, std::vector<double>>;
std::string to_text(const SpecValue& v);

struct Axis {
  std::string key;
  std::vector<SpecValue> values;
};

struct SweepSpec {
  std::string name;
  std::string description;
  std::string text;  // the spec as written, for provenance
  RunParams base;
  std::string base_env = "empty";
  std::vector<Axis> axes;

  std::int64_t size() const;
  // Parameters and environment of run i (0 <= i < size()).
  void run_settings(std::int64_t i, RunParams& p, std::string& env) const;
};

SweepSpec parse_sweep_spec(const std::string& text, const std::string& source_name);
SweepSpec load_sweep_spec(const std::string& path);

// Sets `key` (a parameter name, or the aliases size, start, ic, env) to v.
// Throws SpecError naming the key and its allowed values.
void apply_setting(RunParams& p, std::string& env, const std::string& key, const SpecValue& v);

// Keys apply_setting accepts, for messages.
std::string known_keys();

}  // namespace chaosweep
