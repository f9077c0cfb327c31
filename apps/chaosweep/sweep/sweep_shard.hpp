#pragma once
// Which shard of a sweep this process runs: --shard K/N, or the SLURM array
// task's.
#include <string>

namespace chaosweep {

struct Shard {
  int index = 0, count = 1;
};

// "K/N", or the SLURM array task's shard when `text` is empty: (ID - MIN) /
// STEP of COUNT from SLURM_ARRAY_TASK_*; no shard (the whole sweep) when
// neither the ID nor the COUNT is set. Throws SpecError naming the flag or
// variable.
Shard parse_shard(const std::string& text);

}  // namespace chaosweep
