#pragma once
// `chaosweep merge` of a tune's shards (`chaosweep tune --shard K/N` races
// the cases i with i % N == K, and a case's run_ids depend on the case
// alone: engine/tune/tune_runner.hpp). Unlike a sweep's, a shard's rows are
// not known ahead (a race may stop short of its budget), so a shard is whole
// when its tune finished (end_time set, its rows its runs_total), and the
// merged file holds every shard's rows, shard after shard, as they are.
// Internal to the store (merge_results dispatches here on kind = "tune").
#include <string>
#include <vector>

#include "engine/store/h5_merge.hpp"
#include "engine/store/merge_files.hpp"

namespace chaosweep::merge_detail {

// `inputs` have their provenance read (shard_of), not yet opened.
MergeReport merge_tune_inputs(std::vector<Input>& inputs, const std::string& output, const MergeOptions& options);

// Throws unless the tune shard `in` (opened) finished.
void check_tune_shard_finished(const Input& in);

}  // namespace chaosweep::merge_detail
