#pragma once
// The resume protocol of `chaosweep sweep`: whether OUT may be written, and
// where an interrupted sweep of the same inputs and shard goes on.
#include <cstdint>
#include <memory>
#include <string>

#include "apps/chaosweep/sweep/sweep_shard.hpp"
#include "engine/store/input_identity.hpp"
#include "engine/store/output_lock.hpp"

namespace chaosweep {

struct SweepStart {
  std::unique_ptr<OutputLock> lock;  // held from the checks on: this process is OUT's only writer
  bool complete = false;             // --resume of a complete OUT: nothing to do
  bool resuming = false;             // OUT.partial goes on
  std::int64_t skip = 0;             // runs of the shard OUT.partial holds
};

// Checks `out` (and `out`.partial) against --resume/--force, locks it, and
// for a resume checks that the partial file holds this spec's inputs and
// this shard's first runs: a sweep's run_ids K, K + N, ... when `strided`
// (a tune's run_ids are checked by its replay). Throws std::runtime_error
// (bad input) otherwise.
SweepStart start_sweep_output(const std::string& out, bool resume, bool force, const SweepInputs& inputs, Shard shard,
                              bool strided = true);

}  // namespace chaosweep
