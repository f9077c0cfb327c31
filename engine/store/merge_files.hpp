#pragma once
// Internals shared by the store's two merges (h5_merge.cpp: a sweep's shards,
// run_ids interleaved; tune_merge.cpp: a tune's shards, cases apart): an
// input's place in its sweep from its provenance, the checks that inputs
// belong together, /runs opened for reading in blocks, and the merged file:
// written under a temporary name, renamed when whole. Not for other modules
// (it includes <hdf5.h>).
#include <hdf5.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "engine/store/h5_detail.hpp"
#include "engine/store/h5_store.hpp"

namespace chaosweep::merge_detail {

[[noreturn]] void fail(const std::string& what);
// H5Fclose without HDF5's error dump: its failure (a full disk) is reported
// as the merge's own.
herr_t close_quietly(hid_t file);
[[noreturn]] void fail_write(const std::string& path);

// An input's place in its sweep, from its provenance attributes.
struct ShardOf {
  std::string spec_hash, shard;  // shard as written: "K/N"
  std::string inputs_hash;       // "" when not recorded (an older chaosweep)
  std::string kind;              // "tune" for a tune's file, else ""
  int index = 0, count = 1;
  std::int64_t runs_total = 0;
};
ShardOf shard_of(const std::string& path);

// An input's /runs, open for the whole merge.
struct Input {
  std::string path;
  ShardOf shard;
  std::unique_ptr<h5::Handle> file, dset, ftype, native;
  hsize_t rows = 0;
};
void open_input(Input& in, std::size_t cache_bytes);

// Throws unless every input has the first's spec_hash, inputs_hash and shard
// count, none is given twice (as a path or as a shard), and each holds the
// columns compare and table read.
void check_inputs_belong_together(const std::vector<Input>& inputs);
// Throws unless every opened input has the first's columns.
void check_same_columns(const std::vector<Input>& inputs);

// Rows [first, first + n) of `in` in row type `type` into `buf`; reclaim()
// frees the strings HDF5 allocated for them.
void read_rows(const Input& in, hsize_t first, hsize_t n, std::vector<unsigned char>& buf, hid_t type);
void reclaim(hid_t type, std::vector<unsigned char>& buf);
// Writes `n` rows of `type` at `buf` to rows [first, first + n) of `dset`;
// false when the write failed (HDF5's error dump held back).
bool write_rows(hid_t dset, hid_t type, hsize_t first, hsize_t n, const void* buf);

// The SIMD targets of every input, each once, in order of first use.
std::string simd_targets(const std::vector<Input>& inputs);
// More inputs than this process may open files: raise the soft limit.
void allow_open_files(std::size_t n);

// The output's chunks: 1024 rows (as a sweep writes), shuffled and deflated.
inline constexpr hsize_t out_chunk_rows = 1024;
inline constexpr int out_deflate_level = 4;

// The merged file being written at `path` (through the rollback driver):
// /runs of `total` rows of `file_type`, chunked and filtered as a sweep
// writes them. Closed (not finished) when destroyed.
class MergedFile {
 public:
  MergedFile(const std::string& path, hsize_t total, hid_t file_type);
  hid_t runs() const { return dset_.id; }
  // Provenance: the first input's but `skip`, "shard" saying what was merged,
  // merged_from, merged_at, every input's simd_target, then `extra`; then
  // closes the file, whose flush fails on a full disk (rolled back, then
  // OutOfRoom).
  void finish(const std::vector<Input>& inputs, std::set<std::string> skip, const std::vector<Attribute>& extra);

 private:
  std::string path_;
  h5::Handle file_{-1, close_quietly}, dset_{-1, H5Dclose};
};

// Calls write(temp) to make the merged file at a temporary name beside
// `output` (after checking there is room for about the inputs' sizes), then
// renames it to `output`; on any failure removes what it wrote and rethrows.
void write_via_temp(const std::vector<Input>& inputs, const std::string& output,
                    const std::function<void(const std::string& temp)>& write);

}  // namespace chaosweep::merge_detail
