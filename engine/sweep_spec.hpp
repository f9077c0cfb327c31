#pragma once
// A sweep spec (TOML): fixed settings, axes whose Cartesian product is the
// set of runs, and zip groups (lists that advance together, e.g. the rows of
// a paper's table). run_id = index in the expansion, the first axis varying
// slowest, axes in file order. A spec may also hold [[part]] tables: each is
// its own product (its fixed settings and axes over the spec's base, then the
// spec's top-level axes), and the runs are the parts' runs one after the
// other in file order. See README.md, "Sweep specs".
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

// What one run is before its environment is loaded.
struct RunSpec {
  RunParams params;
  std::string env = "empty";
  std::string label;  // free text naming the run's case (e.g. a Table 1 row)
};

// The settings an axis applies at one of its positions.
using Settings = std::vector<std::pair<std::string, SpecValue>>;

// An axis: one key (a plain axis), several advancing together (a [[zip]]
// group), or a list of cases ([[case]] tables, one position each).
struct Axis {
  std::string kind = "axis";      // "axis", "zip" or "case"
  std::vector<std::string> keys;  // every key the axis sets
  std::vector<Settings> values;   // values[i]: the settings of position i
  std::size_t size() const { return values.size(); }
  std::string name() const;  // "A", "zip(size, sr)" or "case(label, size, ...)"
};

// A [[part]]: a product of its own over the spec's base. Its runs start from
// the base, apply `fixed`, then its axes (slowest), then the spec's top-level
// axes; a run left without a label gets the part's name as its label.
struct SpecPart {
  std::string name;
  Settings fixed;          // the part's own fixed settings
  std::vector<Axis> axes;  // the part's own axes, in file order
  std::int64_t own_size() const;  // product of the part's own axes (1 if none)
};

struct SweepSpec {
  std::string name;
  std::string description;
  std::string text;  // the spec as written (with any extended spec), for provenance
  RunSpec base;
  // Without parts: the axes of the one product. With parts: the axes every
  // part shares, varying faster than the part's own.
  std::vector<Axis> axes;
  std::vector<SpecPart> parts;  // empty: the spec is one product
  // [repeat]: each run's `seed` = splitmix64 of (master seed, run_id).
  bool repeat = false;
  std::uint64_t master_seed = 0;

  std::int64_t size() const;
  RunSpec run(std::int64_t i) const;  // 0 <= i < size()

  std::int64_t shared_size() const;                 // product of `axes` (1 if none)
  std::int64_t part_size(std::size_t k) const;      // runs of parts[k]
  std::int64_t part_offset(std::size_t k) const;    // run_id of parts[k]'s first run
  std::size_t part_of(std::int64_t run_id) const;   // index of the part holding run_id (parts non-empty)
};

// `source_name` is used in messages; `dir` resolves `extends`.
SweepSpec parse_sweep_spec(const std::string& text, const std::string& source_name,
                           const std::string& dir = ".");
SweepSpec load_sweep_spec(const std::string& path);

// Sets `key` (a parameter name, or size, start, ic, env, label) to v.
// Throws SpecError naming the key and its allowed values.
void apply_setting(RunSpec& r, const std::string& key, const SpecValue& v);

// The seed of run `run_id` under [repeat] with `master`: splitmix64 of
// master + run_id * golden ratio, kept to 53 bits (exact as a double).
std::int64_t repeat_seed(std::uint64_t master, std::int64_t run_id);

// Keys apply_setting accepts, for messages.
std::string known_keys();

}  // namespace chaosweep
