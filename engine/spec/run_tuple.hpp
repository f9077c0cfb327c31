#pragma once
// A run tuple: everything one run needs, resolved (environment loaded, start
// and map size filled in). The data path is spec -> RunTuple -> kernel ->
// RunRow -> HDF5/JSON.
#include <cstdint>
#include <memory>
#include <string>

#include "kernels/core/environment.hpp"
#include "engine/spec/environment_loader.hpp"
#include "kernels/core/run_params.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "kernels/core/trace.hpp"

namespace chaosweep {

struct RunTuple {
  std::int64_t run_id = 0;
  std::string env_spec = "empty";  // as the user wrote it: a name or a path
  std::string label;               // the spec's free-text case name
  RunParams params;
  std::shared_ptr<const Environment> env;
};

struct RunRow {
  RunTuple tuple;
  RunResult result;
};

// Default start when neither the run nor the environment gives one: the
// papers' (0.5 m, 0.5 m).
inline constexpr double default_start = 0.5;

// Loads the environment and fills the map size and an unset start from it.
RunTuple resolve_run(std::int64_t run_id, const RunSpec& spec, EnvironmentCache& cache);

// Runs the kernel, timing it; never throws (an exception becomes status error).
RunRow evaluate(const RunTuple& t, TraceSink* trace = nullptr);

}  // namespace chaosweep
