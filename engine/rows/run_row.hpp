#pragma once
// A run tuple and its row: everything one run needs, resolved (environment
// loaded, start and map size filled in), and the run's result. The data path
// is spec -> RunTuple -> lanes -> RunRow -> HDF5/JSON; these plain types
// depend only on kernels so that the writers of rows (the store, JSON) need
// not see the spec parser that makes tuples (engine/spec/run_tuple.hpp).
#include <cstdint>
#include <memory>
#include <string>

#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"

namespace chaosweep {

struct RunTuple {
  std::int64_t run_id = 0;
  std::string env_spec = "empty";  // as the user wrote it: a name or a path
  std::string label;               // the spec's free-text case name
  RunParams params;
  std::shared_ptr<const Environment> env;
  // `chaosweep tune` (engine/tune): the race iteration (1, 2, ...; 0 for the
  // validation runs) and the configuration within its case; -1 for a sweep.
  std::int64_t race_round = -1;
  std::int64_t config_id = -1;
};

struct RunRow {
  RunTuple tuple;
  RunResult result;
};

}  // namespace chaosweep
