#pragma once
// What a sweep's rows depend on besides the engine: the spec's text (the
// extended specs' included, spec_hash) and the content of every environment
// file its runs load. A result file records each file read (attribute
// input_files: kind, content hash, name, absolute path; one line each) and one hash of
// them all (inputs_hash); --resume and merge compare inputs_hash, so rows made
// on an edited map are never mixed with rows made on the original.
#include <string>
#include <vector>

#include "engine/spec/environment_loader.hpp"
#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

struct InputFile {
  std::string kind;  // "spec", "extends" or "env"
  std::string name;  // as the spec gives it (a spec file: its path)
  InputRecord file;  // path and content hash
};

struct SweepInputs {
  std::string spec_hash;         // of the spec's text
  std::vector<InputFile> files;  // the specs, then the environments by name
  std::string hash() const;      // inputs_hash: spec_hash and each environment's name and content
  std::string text() const;      // the input_files attribute
};

// The inputs of `spec` (loaded from `spec_path`), whose environments are in
// `cache` (preload_environments).
SweepInputs sweep_inputs(const SweepSpec& spec, const EnvironmentCache& cache);

// The files that differ between two input_files texts, for messages:
// "env1.toml changed (environment 'env1.toml')", "x.toml is new (...)",
// "y.toml is no longer read (...)"; "" when none does.
std::string changed_inputs(const std::string& before, const std::string& now);

// Throws std::runtime_error naming `path` (a result or partial file) and what
// changed, unless it was made from the same spec and input files as `now`.
void check_same_inputs(const std::string& path, const SweepInputs& now);

}  // namespace chaosweep
