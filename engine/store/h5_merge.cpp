#include "engine/store/h5_merge.hpp"

#include <hdf5.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <memory>
#include <set>
#include <stdexcept>

#include "engine/spec/shard.hpp"
#include "engine/store/chunk_filters.hpp"
#include "engine/store/disk_room.hpp"
#include "engine/store/global_heap_text.hpp"
#include "engine/store/h5_detail.hpp"
#include "engine/store/h5_file_rows.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/input_identity.hpp"
#include "engine/store/merge_files.hpp"
#include "engine/store/provenance.hpp"
#include "engine/store/rollback_driver.hpp"
#include "engine/store/tune_merge.hpp"

namespace chaosweep {

namespace fs = std::filesystem;
using h5::Handle;
using namespace merge_detail;

namespace {

// A shard cannot hold more rows than its share of the runs.
void check_row_count(const Input& in, std::int64_t runs_total) {
  const std::int64_t want = shard_size(runs_total, in.shard.index, in.shard.count);
  if (std::int64_t(in.rows) > want)
    fail(in.path + " is damaged: it holds " + std::to_string(in.rows) + " rows, but shard " + in.shard.shard + " of " +
         std::to_string(runs_total) + " runs has " + std::to_string(want));
}

// Shard K of N holds run_ids K, K+N, ... in order (a sweep writes them so):
// any other row means the file is damaged.
bool run_id_is_right(const Input& in, hsize_t j, std::int64_t id) {
  return id == shard_run_id(std::int64_t(j), in.shard.index, in.shard.count);
}

void check_run_id(const Input& in, hsize_t j, std::int64_t id, std::int64_t runs_total) {
  if (run_id_is_right(in, j, id)) return;
  const std::int64_t expect = shard_run_id(std::int64_t(j), in.shard.index, in.shard.count);
  const std::string row = "row " + std::to_string(j) + " has run_id " + std::to_string(id);
  if (id < 0 || id >= runs_total)
    fail(in.path + " is damaged: " + row + ", outside the spec's runs 0.." + std::to_string(runs_total - 1) +
         " (re-run shard " + in.shard.shard + ")");
  fail(in.path + " is damaged: " + row + ", not " + std::to_string(expect) + " (shard " + in.shard.shard +
       " holds run_ids " + std::to_string(in.shard.index) + ", " + std::to_string(in.shard.index + in.shard.count) +
       ", ... in order; re-run it)");
}

// run_id of the `n` rows at `rows`, `row_size` bytes apart, run_id at
// `offset`: rows [first, first + n) of shard `in`.
void check_run_ids(const Input& in, hsize_t first, hsize_t n, const unsigned char* rows, std::size_t row_size,
                   std::size_t offset, std::int64_t runs_total) {
  for (hsize_t r = 0; r < n; ++r) {
    std::int64_t id;
    std::memcpy(&id, rows + std::size_t(r) * row_size + offset, 8);
    check_run_id(in, first + r, id, runs_total);
  }
}

// Where run_id sits in a row of `type` (H5Dget_type's or native), when it is
// a 64-bit integer as a sweep writes it; npos otherwise (a hand-made file:
// its run_ids are read through HDF5's conversion before the merge).
std::size_t int64_run_id_offset(hid_t type) {
  const int i = H5Tget_member_index(type, "run_id");
  if (i < 0) return std::string::npos;
  Handle mt{H5Tget_member_type(type, unsigned(i)), H5Tclose};
  return H5Tequal(mt.id, H5T_NATIVE_INT64) > 0 ? H5Tget_member_offset(type, unsigned(i)) : std::string::npos;
}

// Every run_id of `in`, read in blocks: for a merge that writes nothing (runs
// are missing), which must still name a damaged shard. A merge that writes
// checks each block as it copies it.
void check_all_run_ids(const Input& in, std::int64_t runs_total) {
  Handle mem{H5Tcreate(H5T_COMPOUND, 8), H5Tclose};
  H5Tinsert(mem.id, "run_id", 0, H5T_NATIVE_INT64);
  std::vector<unsigned char> buf;
  const hsize_t block = hsize_t(1) << 20;
  for (hsize_t first = 0; first < in.rows; first += block) {
    const hsize_t n = std::min(block, in.rows - first);
    read_rows(in, first, n, buf, mem.id);
    check_run_ids(in, first, n, buf.data(), 8, 0, runs_total);
  }
}

// Raw blocks hold at least a chunk of every shard unfiltered: merges of more
// shards than fit take the converting path alone.
constexpr std::size_t raw_block_cap = std::size_t(256) << 20;

// Rows [j0, j1) of every shard, `step` at a time, through HDF5's conversion
// (the path that handles any row: variable-length text has heap ids of its
// own file, so it must be read and written as strings).
void write_converted(const std::vector<const Input*>& by_index, hid_t dset, hid_t type, hsize_t total, hsize_t j0,
                     hsize_t j1, hsize_t step, const std::string& path) {
  const hsize_t count = by_index.size();
  const std::size_t rs = H5Tget_size(type);
  const std::size_t run_id_at = int64_run_id_offset(type);  // npos: checked before
  std::vector<std::vector<unsigned char>> part(by_index.size());
  // The strings HDF5 allocated for the rows read, freed also when a check
  // below throws (a damaged shard) or the write fails.
  struct Reclaim {
    hid_t type;
    std::vector<std::vector<unsigned char>>& part;
    void operator()() {
      for (auto& p : part) {
        reclaim(type, p);
        p.clear();
      }
    }
    ~Reclaim() { (*this)(); }
  } reclaim_parts{type, part};
  std::vector<unsigned char> out;
  for (hsize_t j = j0; j < j1; j += step) {
    const hsize_t first = j * count;
    const hsize_t n = std::min<hsize_t>(total, std::min(j + step, j1) * count) - first;
    out.assign(std::size_t(n) * rs, 0);
    for (hsize_t k = 0; k < count; ++k) {
      if (!by_index[k]) continue;  // a shard of no runs (more shards than runs)
      const Input& in = *by_index[k];
      const hsize_t have = j < in.rows ? std::min({step, j1 - j, in.rows - j}) : 0;
      read_rows(in, j, have, part[k], type);
      if (run_id_at != std::string::npos)
        check_run_ids(in, j, have, part[k].data(), rs, run_id_at, std::int64_t(total));
      for (hsize_t i = 0; i < have; ++i)
        std::memcpy(out.data() + std::size_t(i * count + k) * rs, part[k].data() + std::size_t(i) * rs, rs);
    }
    const bool written = write_rows(dset, type, first, n, out.data());
    reclaim_parts();  // the strings `out` pointed to too
    if (!written) fail_write(path);
  }
}

// What read_raw_block found: chunks not as expected (the block then takes
// the converting path), rows that can be copied as bytes, or rows holding
// variable-length text (heap ids of their own file, which a copy would leave
// dangling: written as strings, write_text_block).
enum class RawBlock { unusable, bytes, text };

// Rows [j0, j0 + per_shard) of every shard as the files store them (`rows`,
// per shard), their whole chunks read raw and unfiltered on many threads.
RawBlock read_raw_block(const std::vector<const Input*>& by_index, hsize_t j0, hsize_t per_shard, const FileRows& f,
                        std::size_t run_id_at, std::int64_t runs_total, const ParallelFor& parallel,
                        std::vector<std::vector<unsigned char>>& rows) {
  const std::size_t chunk_bytes = std::size_t(out_chunk_rows) * f.row_size;
  struct Task {
    std::size_t shard;
    hsize_t chunk;  // first row, in the shard
    std::vector<unsigned char> stored;
  };
  std::vector<Task> tasks;
  for (std::size_t k = 0; k < by_index.size(); ++k) {
    if (!by_index[k]) continue;
    const Input& in = *by_index[k];
    rows[k].resize(std::size_t(per_shard) * f.row_size);
    for (hsize_t c = j0; c < std::min(j0 + per_shard, in.rows); c += out_chunk_rows) {
      hsize_t size = 0;
      std::uint32_t mask = 0;
      if (H5Dget_chunk_storage_size(in.dset->id, &c, &size) < 0 || size == 0) return RawBlock::unusable;
      Task t{k, c, std::vector<unsigned char>(size)};
      herr_t rc;
      H5E_BEGIN_TRY { rc = H5Dread_chunk(in.dset->id, H5P_DEFAULT, &c, &mask, t.stored.data()); }
      H5E_END_TRY;
      if (rc < 0 || mask != 0) return RawBlock::unusable;
      tasks.push_back(std::move(t));
    }
  }
  std::atomic<bool> ok{true}, wrong_id{false}, text{false};
  run_parallel(parallel, tasks.size(), [&](std::size_t i) {
    const Task& t = tasks[i];
    const Input& in = *by_index[t.shard];
    thread_local std::vector<unsigned char> shuffled_bytes;  // a chunk's worth, kept: no page faults per chunk
    shuffled_bytes.resize(chunk_bytes);
    if (!inflate_exactly(t.stored.data(), t.stored.size(), shuffled_bytes.data(), chunk_bytes)) {
      ok = false;
      return;
    }
    unsigned char* dst = rows[t.shard].data() + std::size_t(t.chunk - j0) * f.row_size;
    unshuffle(shuffled_bytes.data(), chunk_bytes, f.row_size, dst);
    const hsize_t valid = std::min(out_chunk_rows, in.rows - t.chunk);
    for (hsize_t r = 0; r < valid; ++r) {
      const unsigned char* row = dst + std::size_t(r) * f.row_size;
      std::int64_t id;
      std::memcpy(&id, row + run_id_at, 8);
      if (!run_id_is_right(in, t.chunk + r, id)) wrong_id = true;
      for (std::size_t m = 0; m < f.offsets.size(); ++m) {
        if (!f.variable_text[m]) continue;
        const unsigned char* p = row + f.offsets[m];
        if (!empty_variable_text(p)) text = true;
      }
    }
  });
  // The damaged row named is the first, as a serial check names it.
  if (ok && wrong_id)
    for (const Task& t : tasks) {
      const Input& in = *by_index[t.shard];
      check_run_ids(in, t.chunk, std::min(out_chunk_rows, in.rows - t.chunk),
                    rows[t.shard].data() + std::size_t(t.chunk - j0) * f.row_size, f.row_size, run_id_at, runs_total);
    }
  return !ok ? RawBlock::unusable : text ? RawBlock::text : RawBlock::bytes;
}

// Where each member sits in a row of memory type `type` and how wide it
// is, for rows read raw (file layout `f`) and written through HDF5; empty
// when a number is not stored as `type` holds it.
struct MemoryRows {
  std::size_t row_size = 0;
  std::vector<std::size_t> offsets, sizes;
};
MemoryRows memory_rows(hid_t type, hid_t ftype, const FileRows& f) {
  MemoryRows m;
  m.row_size = H5Tget_size(type);
  for (unsigned i = 0; i < unsigned(f.offsets.size()); ++i) {
    Handle mt{H5Tget_member_type(type, i), H5Tclose}, ft{H5Tget_member_type(ftype, i), H5Tclose};
    if (!f.variable_text[i] && H5Tequal(mt.id, ft.id) <= 0) return {};
    m.offsets.push_back(H5Tget_member_offset(type, i));
    m.sizes.push_back(H5Tget_size(mt.id));
  }
  return m;
}

// Interleaves `rows` (a raw block of every shard, holding text) into rows of
// memory type `type` (layout `m`), each string read from its shard's heap,
// and writes them through HDF5, which puts the strings in the output's
// heap. False (nothing written) when a string cannot be read so: the block
// then takes the converting path, which names a damaged shard. `out`: the
// rows' buffer, kept from block to block (a new one is page-faulted in).
bool write_text_block(const std::vector<std::vector<unsigned char>>& rows, hsize_t j0, hsize_t per_shard,
                      const FileRows& f, const MemoryRows& m, std::vector<std::unique_ptr<GlobalHeapText>>& heaps,
                      hid_t dset, hid_t type, hsize_t total, const std::string& path, std::vector<unsigned char>& out) {
  const hsize_t count = rows.size(), first = j0 * count;
  const hsize_t n = std::min(total, (j0 + per_shard) * count) - first;
  out.assign(std::size_t(n) * m.row_size, 0);
  std::deque<std::string> texts;
  for (hsize_t r = 0; r < n; ++r) {
    const hsize_t run = first + r, k = run % count, j = run / count - j0;
    const unsigned char* src = rows[k].data() + std::size_t(j) * f.row_size;
    unsigned char* dst = out.data() + std::size_t(r) * m.row_size;
    for (std::size_t i = 0; i < m.offsets.size(); ++i) {
      const unsigned char* p = src + f.offsets[i];
      if (!f.variable_text[i]) {
        std::memcpy(dst + m.offsets[i], p, m.sizes[i]);
        continue;
      }
      // All zero: a null string, as HDF5 reads it (the converting path's).
      if (empty_variable_text(p)) continue;
      if (!heaps[k] || !heaps[k]->usable() || !heaps[k]->text(p, texts.emplace_back())) return false;
      const char* c = texts.back().c_str();
      std::memcpy(dst + m.offsets[i], &c, sizeof c);
    }
  }
  if (!write_rows(dset, type, first, n, out.data())) fail_write(path);
  return true;
}

// Interleaves `rows` (a raw block of every shard) into the output's chunks,
// filters them on many threads and writes them as they are.
void write_raw_block(const std::vector<std::vector<unsigned char>>& rows, hsize_t j0, hsize_t per_shard,
                     const FileRows& f, hid_t dset, hsize_t total, const ParallelFor& parallel,
                     const std::string& path) {
  const hsize_t count = rows.size(), first = j0 * count;
  const hsize_t n = std::min(total, (j0 + per_shard) * count) - first;
  const std::size_t chunks = std::size_t((n + out_chunk_rows - 1) / out_chunk_rows);
  std::vector<std::vector<unsigned char>> stored(chunks);
  run_parallel(parallel, chunks, [&](std::size_t o) {
    // The last chunk's rows past the end are zeros, as HDF5 pads them.
    thread_local std::vector<unsigned char> chunk;
    chunk.assign(std::size_t(out_chunk_rows) * f.row_size, 0);
    const hsize_t r0 = hsize_t(o) * out_chunk_rows, r1 = std::min(n, r0 + out_chunk_rows);
    for (hsize_t r = r0; r < r1; ++r) {
      const hsize_t run = first + r, k = run % count, j = run / count - j0;
      std::memcpy(chunk.data() + std::size_t(r - r0) * f.row_size, rows[k].data() + std::size_t(j) * f.row_size,
                  f.row_size);
    }
    stored[o] = shuffled_and_deflated(chunk.data(), chunk.size(), f.row_size, out_deflate_level);
  });
  for (std::size_t o = 0; o < chunks; ++o) {
    const hsize_t at = first + hsize_t(o) * out_chunk_rows;
    herr_t rc;
    H5E_BEGIN_TRY { rc = H5Dwrite_chunk(dset, H5P_DEFAULT, 0, &at, stored[o].size(), stored[o].data()); }
    H5E_END_TRY;
    if (rc < 0) fail_write(path);
  }
}

// Writes the inputs' rows interleaved by run_id to `path` (created): blocks
// of whole chunks copied as bytes where every input allows (filters undone
// and redone on many threads: no type conversion), the rest converted.
// Returns the blocks written through HDF5's conversion of the shards' rows.
std::int64_t write_merged(std::vector<Input>& inputs, const std::string& path, std::int64_t total, hsize_t per_shard,
                          const MergeOptions& options) {
  const int count = inputs[0].shard.count;
  std::vector<const Input*> by_index(std::size_t(count), nullptr);
  for (const Input& in : inputs) by_index[std::size_t(in.shard.index)] = &in;
  const hid_t type = inputs[0].native->id;
  MergedFile out(path, hsize_t(total), inputs[0].ftype->id);
  const hid_t dset = out.runs();
  const FileRows out_rows = file_rows_of(dset);
  // The file type's run_id (its members in memory order, as H5Dget_type gives).
  std::size_t run_id_at = std::string::npos;
  {
    Handle ftype{H5Dget_type(dset), H5Tclose};
    const int i = H5Tget_member_index(ftype.id, "run_id");
    if (int64_run_id_offset(ftype.id) != std::string::npos && out_rows.row_size > 0)
      run_id_at = out_rows.offsets[unsigned(i)];
  }
  bool raw = out_rows.row_size > 0 && run_id_at != std::string::npos &&
             int64_run_id_offset(type) != std::string::npos &&
             std::size_t(count) * out_chunk_rows * out_rows.row_size <= raw_block_cap;
  for (const Input& in : inputs) {
    const FileRows in_rows = file_rows_of(in.dset->id);
    raw = raw && in_rows.row_size == out_rows.row_size && in_rows.offsets == out_rows.offsets &&
          in_rows.deflate_level >= 0 && in_rows.chunk_rows == out_chunk_rows;
  }
  const hsize_t shard_rows = hsize_t(shard_size(total, 0, count));
  std::int64_t converted = 0;
  if (!raw) {
    write_converted(by_index, dset, type, hsize_t(total), 0, shard_rows, per_shard, path);
    converted = std::int64_t((shard_rows + per_shard - 1) / per_shard);
  } else {
    const hsize_t chunk_set = hsize_t(count) * out_chunk_rows * out_rows.row_size;
    const hsize_t block = out_chunk_rows * std::clamp<hsize_t>(options.block_bytes / chunk_set, 1, 64);
    std::vector<std::vector<unsigned char>> rows(by_index.size());
    const MemoryRows mem = memory_rows(type, inputs[0].ftype->id, out_rows);
    std::vector<std::unique_ptr<GlobalHeapText>> heaps(by_index.size());  // made at a shard's first text
    std::vector<unsigned char> text_rows;
    for (hsize_t j0 = 0; j0 < shard_rows; j0 += block) {
      const RawBlock got = read_raw_block(by_index, j0, block, out_rows, run_id_at, total, options.parallel, rows);
      if (got == RawBlock::text && !mem.offsets.empty())
        for (std::size_t k = 0; k < by_index.size(); ++k)
          if (by_index[k] && !heaps[k]) heaps[k] = std::make_unique<GlobalHeapText>(by_index[k]->file->id);
      if (got == RawBlock::bytes)
        write_raw_block(rows, j0, block, out_rows, dset, hsize_t(total), options.parallel, path);
      else if (got != RawBlock::text || mem.offsets.empty() ||
               !write_text_block(rows, j0, block, out_rows, mem, heaps, dset, type, hsize_t(total), path, text_rows)) {
        write_converted(by_index, dset, type, hsize_t(total), j0, std::min(j0 + block, shard_rows), out_chunk_rows,
                        path);
        ++converted;
      }
    }
  }
  out.finish(inputs, {}, {});
  return converted;
}

}  // namespace

std::string merge_temp_path(const std::string& output) { return output + ".merging"; }

namespace {

// "1,4,7", the first 20 and a count beyond.
std::string shard_list(const std::vector<int>& shards) {
  std::string s;
  for (std::size_t i = 0; i < shards.size(); ++i) {
    if (i == 20) return s + ",... (" + std::to_string(shards.size()) + " shards)";
    if (i > 0) s += ',';
    s += std::to_string(shards[i]);
  }
  return s;
}

}  // namespace

std::string MergeReport::text() const {
  if (tune) {
    std::string s = std::to_string(rows) + " rows of a tune in " + std::to_string(shard_count) + " shards";
    if (missing == 0) return s;
    const std::string shards = shard_list(shards_to_rerun);
    s += "\nmissing shards ";
    s += shards + " of " + std::to_string(shard_count) + " (e.g. chaosweep tune SPEC -o OUT --shard " +
         std::to_string(shards_to_rerun.front()) + "/" + std::to_string(shard_count) + " --resume)";
    return s;
  }
  std::string s = std::to_string(rows) + " rows of " + std::to_string(runs_total) + " runs";
  if (missing > 0) {
    std::string ids;
    for (std::size_t i = 0; i < first_missing.size(); ++i) ids += (i ? ", " : "") + std::to_string(first_missing[i]);
    s += "\nmissing " + std::to_string(missing) + " runs (run_id " + ids +
         (missing > std::int64_t(first_missing.size()) ? ", ..." : "") + ")";
    const std::string shards = shard_list(shards_to_rerun);
    s += "\nre-run shards " + shards + " of " + std::to_string(shard_count) +
         " (e.g. chaosweep sweep SPEC -o OUT --shard " + std::to_string(shards_to_rerun.front()) + "/" +
         std::to_string(shard_count) + " --resume)";
  }
  return s;
}

std::string check_shard_file(const std::string& path, int index, int count, std::int64_t runs_total) {
  const ShardOf s = shard_of(path);
  const std::string want = std::to_string(index) + "/" + std::to_string(count);
  if (s.shard != want) fail(path + " is shard " + s.shard + ", not " + want + " (of another sweep)");
  if (s.runs_total != runs_total)
    fail(path + " has runs_total " + std::to_string(s.runs_total) + ", not the sweep's " + std::to_string(runs_total) +
         " (of another sweep)");
  check_result_columns(path);
  return s.spec_hash + "\t" + s.inputs_hash;
}

MergeReport merge_results(const std::vector<std::string>& paths, const std::string& output,
                          const MergeOptions& options) {
  if (paths.empty()) fail("no input files");
  MergeReport report;
  std::vector<Input> inputs(paths.size());
  for (std::size_t f = 0; f < paths.size(); ++f) {
    inputs[f].path = paths[f];
    inputs[f].shard = shard_of(paths[f]);
  }
  for (std::size_t f = 0; f < inputs.size(); ++f)
    if ((inputs[f].shard.kind == "tune") != (inputs[0].shard.kind == "tune"))
      fail(paths[f] + " and " + paths[0] + " are not both a tune's shards (one is a sweep's): they cannot be merged");
  if (inputs[0].shard.kind == "tune") return merge_tune_inputs(inputs, output, options);
  report.runs_total = inputs[0].shard.runs_total;
  report.shard_count = inputs[0].shard.count;
  check_inputs_belong_together(inputs);
  for (std::size_t f = 0; f < inputs.size(); ++f)
    if (inputs[f].shard.runs_total != report.runs_total)
      fail(paths[f] + " has runs_total " + std::to_string(inputs[f].shard.runs_total) + " but " + paths[0] + " has " +
           std::to_string(report.runs_total));
  allow_open_files(inputs.size());
  std::size_t row_size = 0;
  {
    Input probe;
    probe.path = paths[0];
    open_input(probe, 0);
    row_size = H5Tget_size(probe.native->id);
  }
  // As many rows of each shard per block as fit, up to a chunk (1024 rows):
  // whole chunks need no chunk cache; fewer keep one chunk cached.
  const hsize_t per_shard =
      std::clamp<hsize_t>(hsize_t(options.block_bytes / (std::max<std::size_t>(row_size, 1) * inputs.size())), 1, 1024);
  const std::size_t cache = per_shard < 1024 ? 1024 * row_size + 4096 : 0;
  for (std::size_t f = 0; f < inputs.size(); ++f) {
    open_input(inputs[f], cache);
    check_row_count(inputs[f], report.runs_total);
    report.rows += std::int64_t(inputs[f].rows);
  }
  check_same_columns(inputs);
  // Missing runs: the rest of each shard (none of an absent shard).
  std::vector<std::int64_t> have(std::size_t(report.shard_count), 0);
  for (const Input& in : inputs) have[std::size_t(in.shard.index)] = std::int64_t(in.rows);
  for (int k = 0; k < report.shard_count; ++k) {
    const std::int64_t want = shard_size(report.runs_total, k, report.shard_count);
    if (have[std::size_t(k)] >= want) continue;
    report.missing += want - have[std::size_t(k)];
    report.shards_to_rerun.push_back(k);
    for (std::int64_t j = have[std::size_t(k)]; j < want && j < have[std::size_t(k)] + 10; ++j)
      report.first_missing.push_back(shard_run_id(j, k, report.shard_count));
  }
  std::sort(report.first_missing.begin(), report.first_missing.end());
  if (report.first_missing.size() > 10) report.first_missing.resize(10);
  // A merge that writes checks the run_ids of each block it copies (one pass
  // over the rows); one that does not, or of rows it cannot read so, here.
  if (!report.ok() || int64_run_id_offset(inputs[0].native->id) == std::string::npos) {
    for (const Input& in : inputs) check_all_run_ids(in, report.runs_total);
    if (!report.ok()) return report;
  }

  write_via_temp(inputs, output, [&](const std::string& temp) {
    report.blocks_converted = write_merged(inputs, temp, report.runs_total, per_shard, options);
  });
  return report;
}

}  // namespace chaosweep
