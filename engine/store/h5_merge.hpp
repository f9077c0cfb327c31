#pragma once
// `chaosweep merge`: shard files of one sweep into one result file, rows
// sorted by run_id, after checking that the shards belong together, that
// each is intact (shard K of N holds run_ids K, K+N, ... in order: a row
// with any other run_id, one outside the spec's range included, names the
// shard as damaged) and that no run is missing. Memory is bounded by the
// shard count, not the run count: rows are read and written in blocks,
// whole chunks copied as the files store them (unfiltered and filtered again
// on many threads) wherever no variable-length text is in them.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/store/h5_store.hpp"

namespace chaosweep {

struct MergeOptions {
  // Where the chunks are unfiltered and filtered again (e.g. a
  // ThreadBatchEvaluator's threads); none: this thread.
  ParallelFor parallel;
  // Rows read and written at once, in bytes: a block takes as many rows of
  // every shard as fit (at least a chunk each where rows are copied as the
  // files store them, at least one each where they are converted).
  std::size_t block_bytes = std::size_t(64) << 20;
};

struct MergeReport {
  std::int64_t runs_total = 0, rows = 0;
  std::int64_t missing = 0;                 // runs no shard holds (a tune's: shards not given)
  std::vector<std::int64_t> first_missing;  // the smallest of them (at most 10; none for a tune)
  std::vector<int> shards_to_rerun;         // shard indices holding missing runs
  int shard_count = 1;
  bool tune = false;  // the shards of `chaosweep tune --shard` (engine/store/tune_merge.hpp)
  // Blocks of rows written through HDF5's conversion of the shards' rows
  // (the slow path; none for shards a sweep of this engine wrote).
  std::int64_t blocks_converted = 0;
  bool ok() const { return missing == 0; }
  std::string text() const;
};

// Where merge_results writes before renaming to `output` (never
// output.partial, which belongs to a sweep of `output`).
std::string merge_temp_path(const std::string& output);

// Checks `inputs` (a sweep's shards, or a tune's: tune_merge.hpp); when every run is there, writes `output` (via
// merge_temp_path, renamed at the end). Throws std::runtime_error when the
// inputs are not intact shards of one sweep, OutOfRoom (disk_room.hpp) when
// the output cannot fit or a write of it fails; nothing is left of it then.
// The caller holds OUT's lock.
MergeReport merge_results(const std::vector<std::string>& inputs, const std::string& output,
                          const MergeOptions& options = {});

// Throws std::runtime_error naming `path` and what is wrong unless its
// attributes and columns make it shard `index` of `count` of a
// `runs_total`-run sweep, as merge checks each input: its shard and
// runs_total attributes and the columns compare and table need (not its
// rows: merge reads every run_id, which a census must not, since even one
// row costs a whole chunk's decompression). `chaosweep status` checks
// finished shards so: one of another sweep is damaged, not finished.
// Returns what merge compares between shards: spec_hash and inputs_hash.
std::string check_shard_file(const std::string& path, int index, int count, std::int64_t runs_total);
// The same for shard `index` of `count` of a tune (`chaosweep tune --shard`),
// whose rows are not known ahead: the tune must have finished.
std::string check_tune_shard_file(const std::string& path, int index, int count);

}  // namespace chaosweep
