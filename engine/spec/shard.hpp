#pragma once
// Which run_ids shard K of N holds: strided (K, K+N, ...), so that each shard
// samples the whole grid. Shared by the runner, the store's merge and the CLI.

#include <cstdint>

namespace chaosweep {

inline std::int64_t shard_size(std::int64_t total, int index, int count) {
  return index < total ? (total - index + count - 1) / count : 0;
}
inline std::int64_t shard_run_id(std::int64_t j, int index, int count) { return index + j * std::int64_t(count); }

}  // namespace chaosweep
