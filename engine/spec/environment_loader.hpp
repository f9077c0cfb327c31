#pragma once
// Environments are data (docs/spec.md §1): a built-in name or a TOML file. See
// experiments/envs/README.md for the file format.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>

#include "engine/spec/input_file.hpp"
#include "kernels/core/environment.hpp"

namespace chaosweep {

// Loads `spec` (a built-in name such as "empty", a name found as NAME.toml in
// $CHAOSWEEP_ENV_PATH or among the built-in environments, or a path to a .toml
// file) for a map whose side is size_x x size_y unless the file fixes its own
// size. Throws std::runtime_error naming the file and the offending key. When
// a file is read and `source` is given, it receives the file's path and hash.
Environment load_environment(const std::string& spec, double size_x, double size_y, InputRecord* source = nullptr);
// The same from the file's text (`source_name` for messages); for tools and
// the fuzz target. Throws std::runtime_error naming the source and the key.
Environment parse_environment(const std::string& text, const std::string& source_name, double size_x, double size_y);

// Where an environment name is looked up first: NAME.toml in the directories of
// $CHAOSWEEP_ENV_PATH (colon-separated, the first that has it); empty if none.
std::string find_environment_file(const std::string& name);
// Then among the built-in environments: experiments/envs/NAME.toml as it was
// when the binary was built (embedded, so no source tree is needed); nullopt
// for any other name.
std::optional<std::string_view> builtin_environment(const std::string& name);

// Loads each (spec, size) once; shared by all runs of a sweep.
// Thread-safe: a sweep's threads resolve their runs through one cache. Each
// thread remembers its last lookup (which cache, key and entry), so runs of
// one map in a row take no lock (a lock per run kept two threads waiting on
// each other); that entry stays alive until the thread's next lookup.
class EnvironmentCache {
 public:
  EnvironmentCache();
  std::shared_ptr<const Environment> get(const std::string& spec, double size_x, double size_y);
  // The file behind each environment loaded so far that came from one,
  // keyed by the name the spec gives ("one_square", "envs/box.toml:3").
  std::map<std::string, InputRecord> files() const;

 private:
  std::uint64_t id_;  // unique per cache, for the threads' last lookups
  mutable std::mutex mutex_;
  std::map<std::tuple<std::string, double, double>, std::shared_ptr<const Environment>> cache_;
  std::map<std::string, InputRecord> files_;
};

}  // namespace chaosweep
