#pragma once
// A sweep spec (TOML): fixed settings, axes whose Cartesian product is the
// set of runs, and zip groups (lists that advance together, e.g. the rows of
// a paper's table). run_id = index in the expansion, the first axis varying
// slowest, axes in file order. A spec may also hold [[part]] tables: each is
// its own product (its fixed settings and axes over the spec's base, then the
// spec's top-level axes), and the runs are the parts' runs one after the
// other in file order. See docs/sweep_specs.md.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "engine/spec/input_file.hpp"
#include "engine/spec/spec_overrides.hpp"
#include "kernels/core/run_params.hpp"

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

// A [sample] axis: n points computed on demand from the seed, never stored,
// so a sample of millions of points costs no memory until its runs run.
// (With no dimensions it is [repeat]'s n positions, which set nothing.)
struct Sampler {
  struct Dim {
    std::string key;
    double lo = 0, hi = 0;           // a {min, max} range ...
    std::vector<SpecValue> choices;  // ... or a list to pick from
    std::uint64_t perm_key = 0, jitter_key = 0;
  };
  bool lhs = true;  // Latin hypercube; false: independent uniform draws
  std::int64_t n = 0;
  std::vector<Dim> dims;
  Settings at(std::int64_t i) const;  // point i, 0 <= i < n
};

// An axis: one key (a plain axis), several advancing together (a [[zip]]
// group), a list of cases ([[case]] tables, one position each), or a sample.
struct Axis {
  std::string kind = "axis";               // "axis", "zip", "case", "sample" or "repeat"
  std::vector<std::string> keys;           // every key the axis sets
  std::vector<Settings> values;            // values[i]: the settings of position i (not for samples)
  std::shared_ptr<const Sampler> sampler;  // samples: positions computed, not stored
  std::size_t size() const { return sampler ? std::size_t(sampler->n) : values.size(); }
  // Calls f(key, value) for each setting of position i.
  template <class F>
  void visit(std::size_t i, F&& f) const {
    if (sampler) {
      for (const auto& kv : sampler->at(std::int64_t(i))) f(kv.first, kv.second);
    } else {
      for (const auto& kv : values[i]) f(kv.first, kv.second);
    }
  }
  std::string name() const;  // "A", "zip(size, sr)" or "case(label, size, ...)"
};

// A bijection of [0, n) keyed by `key` (Latin-hypercube strata without a
// stored permutation).
std::uint64_t permute_index(std::uint64_t i, std::uint64_t n, std::uint64_t key);

// A [[part]]: a product of its own over the spec's base. Its runs start from
// the base, apply `fixed`, then its axes (slowest), then the spec's top-level
// axes; a run left without a label gets the part's name as its label.
struct SpecPart {
  std::string name;
  Settings fixed;                 // the part's own fixed settings
  std::vector<Axis> axes;         // the part's own axes, in file order
  std::int64_t own_size() const;  // product of the part's own axes (1 if none)
};

struct SweepSpec {
  std::string name;
  std::string description;
  std::string text;  // the spec as written (with any extended spec), for provenance
  // The files it was read from: the spec itself (when loaded from a file),
  // then each spec it extends, in the order read.
  std::vector<InputRecord> files;
  RunSpec base;
  // Without parts: the axes of the one product. With parts: the axes every
  // part shares, varying faster than the part's own.
  std::vector<Axis> axes;
  std::vector<SpecPart> parts;  // empty: the spec is one product
  // [repeat]: each run's `seed` = splitmix64 of (master seed, run_id).
  bool repeat = false;
  std::uint64_t master_seed = 0;
  // The [tune] table as TOML text ("" when none): the spec's runs are then
  // the cases `chaosweep tune` races (engine/tune/tune_spec.hpp), not runs to sweep.
  std::string tune;

  std::int64_t size() const;
  RunSpec run(std::int64_t i) const;  // 0 <= i < size()
  // A run for every combination of the axes that set env or the map size
  // (other axes at their first value), per part: each environment the runs
  // load, without visiting every run.
  std::vector<struct MapVariant> environment_variants() const;

  std::int64_t shared_size() const;                // product of `axes` (1 if none)
  std::int64_t part_size(std::size_t k) const;     // runs of parts[k]
  std::int64_t part_offset(std::size_t k) const;   // run_id of parts[k]'s first run
  std::size_t part_of(std::int64_t run_id) const;  // index of the part holding run_id (parts non-empty)
};

// One of SweepSpec::environment_variants: a run, and where in the spec its
// map comes from ("fixed", "env[2]", "part 'IS', case(label, env)[1]").
struct MapVariant {
  RunSpec run;
  std::string origin;
};

// `source_name` is used in messages; `dir` resolves `extends`. A spec
// that sets nothing, or an `extends` chain that comes back to a spec of the
// chain, is refused (SpecError).
SweepSpec parse_sweep_spec(const std::string& text, const std::string& source_name, const std::string& dir = ".");
// `overrides` (--set, engine/spec/spec_overrides.hpp) change the file's text
// before it is parsed; the spec's text (and so its hash) is the changed one.
SweepSpec load_sweep_spec(const std::string& path, const std::vector<SpecOverride>& overrides = {});

// Sets `key` (a parameter name, or size, start, ic, env, label) to v.
// Throws SpecError naming the key and its allowed values.
void apply_setting(RunSpec& r, const std::string& key, const SpecValue& v);

// The seed of run `run_id` under [repeat] with `master`: splitmix64 of
// master + run_id * golden ratio, kept to 53 bits (exact as a double).
std::int64_t repeat_seed(std::uint64_t master, std::int64_t run_id);

// Keys apply_setting accepts, for messages.
std::string known_keys();

}  // namespace chaosweep
