#pragma once
// `chaosweep merge`: shard files of one sweep into one result file, rows
// sorted by run_id, after checking that the shards belong together and that
// no run is missing or duplicated.
#include <cstdint>
#include <string>
#include <vector>

namespace chaosweep {

struct MergeReport {
  std::int64_t runs_total = 0, rows = 0;
  std::vector<std::int64_t> missing;     // run_ids no shard holds
  std::vector<std::int64_t> duplicated;  // run_ids more than one row holds
  std::vector<int> shards_to_rerun;      // shard indices holding missing runs
  int shard_count = 1;
  bool ok() const { return missing.empty() && duplicated.empty(); }
  std::string text() const;
};

// Checks `inputs`; when everything is there, writes `output` (via
// output.partial, renamed at the end). Throws std::runtime_error when the
// inputs are not shards of one sweep.
MergeReport merge_results(const std::vector<std::string>& inputs, const std::string& output);

}  // namespace chaosweep
