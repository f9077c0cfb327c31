#pragma once
// A spec's run resolved into a run tuple (engine/rows/run_row.hpp).
#include <cstdint>

#include "engine/rows/run_row.hpp"
#include "engine/spec/environment_loader.hpp"
#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

// Default start when neither the run nor the environment gives one: the
// papers' (0.5 m, 0.5 m).
inline constexpr double default_start = 0.5;

// Loads the environment and fills the map size and an unset start from it.
RunTuple resolve_run(std::int64_t run_id, const RunSpec& spec, EnvironmentCache& cache);

}  // namespace chaosweep
