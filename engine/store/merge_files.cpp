#include "engine/store/merge_files.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "engine/store/disk_room.hpp"
#include "engine/store/h5_merge.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/input_identity.hpp"
#include "engine/store/provenance.hpp"
#include "engine/store/rollback_driver.hpp"

namespace chaosweep::merge_detail {

namespace fs = std::filesystem;
using h5::Handle;

namespace {

// Attribute `name` of the open `file` as text (read_attribute's, through one
// open of the file): "" when absent and not `required`.
std::string attribute(hid_t file, const std::string& path, const char* name, bool required = true) {
  Handle attr{-1, H5Aclose};
  H5E_BEGIN_TRY { attr.id = H5Aopen(file, name, H5P_DEFAULT); }
  H5E_END_TRY;
  if (attr.id < 0) {
    if (!required) return {};
    fail(path + " has no attribute '" + name + "' (not a chaosweep result file?)");
  }
  return h5::attribute_text(attr.id, path, name);
}

// Why shard `path` cannot be merged with `first` though their spec is the
// same: the environment files differ (named), or `path` records none.
std::string different_inputs(const std::string& path, const std::string& first, bool unrecorded) {
  if (unrecorded)
    return path +
           " does not record its input files (written by an older chaosweep): whether its environment "
           "files match " +
           first + "'s cannot be checked";
  const std::string changes = changed_inputs(read_attribute(first, "input_files"), read_attribute(path, "input_files"));
  return path + " was made with other input files than " + first + ": " +
         (changes.empty() ? "inputs_hash differs" : changes);
}

}  // namespace

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error(what); }
herr_t close_quietly(hid_t file) {
  herr_t rc;
  H5E_BEGIN_TRY { rc = H5Fclose(file); }
  H5E_END_TRY;
  return rc;
}

[[noreturn]] void fail_write(const std::string& path) {
  throw OutOfRoom("cannot write " + path + " (the disk may be full, or the file-size limit reached: ulimit -f)");
}

ShardOf shard_of(const std::string& path) {
  ShardOf s;
  const Handle file{open_result_file(path), H5Fclose};  // throws naming the file
  s.spec_hash = attribute(file.id, path, "spec_hash");
  s.shard = attribute(file.id, path, "shard");
  try {
    s.inputs_hash = attribute(file.id, path, "inputs_hash", false);
  } catch (const std::exception&) {
  }
  try {
    s.kind = attribute(file.id, path, "kind", false);
  } catch (const std::exception&) {
  }
  const std::string total = attribute(file.id, path, "runs_total");
  char tail = 0;
  if (std::sscanf(s.shard.c_str(), "%d/%d%c", &s.index, &s.count, &tail) != 2 || s.index < 0 || s.count < 1 ||
      s.index >= s.count)
    fail(path + ": attribute 'shard' is '" + s.shard +
         "', not K/N (a merged file cannot be merged again: give its shard files)");
  try {
    std::size_t used = 0;
    s.runs_total = std::stoll(total, &used);
    if (used != total.size() || s.runs_total < 0 || s.runs_total > (std::int64_t(1) << 62))
      throw std::invalid_argument(total);
  } catch (const std::exception&) {
    fail(path + ": attribute 'runs_total' is '" + total + "', not a run count");
  }
  return s;
}

void open_input(Input& in, std::size_t cache_bytes) {
  in.file = std::make_unique<Handle>(open_result_file(in.path), H5Fclose);
  Handle dapl{H5Pcreate(H5P_DATASET_ACCESS), H5Pclose};
  H5Pset_chunk_cache(dapl.id, H5D_CHUNK_CACHE_NSLOTS_DEFAULT, cache_bytes, H5D_CHUNK_CACHE_W0_DEFAULT);
  hid_t d;
  H5E_BEGIN_TRY { d = H5Dopen2(in.file->id, "/runs", dapl.id); }
  H5E_END_TRY;
  if (d < 0) fail(in.path + " has no /runs dataset (not a chaosweep result file)");
  in.dset = std::make_unique<Handle>(d, H5Dclose);
  in.ftype = std::make_unique<Handle>(H5Dget_type(d), H5Tclose);
  in.native = std::make_unique<Handle>(H5Tget_native_type(in.ftype->id, H5T_DIR_ASCEND), H5Tclose);
  Handle space{H5Dget_space(d), H5Sclose};
  H5Sget_simple_extent_dims(space.id, &in.rows, nullptr);
}

// Rows [first, first + n) of `in` in its native row type.
void read_rows(const Input& in, hsize_t first, hsize_t n, std::vector<unsigned char>& buf, hid_t type) {
  buf.assign(std::size_t(n) * H5Tget_size(type), 0);
  if (n == 0) return;
  Handle fspace{H5Dget_space(in.dset->id), H5Sclose};
  H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, &first, nullptr, &n, nullptr);
  Handle mspace{H5Screate_simple(1, &n, nullptr), H5Sclose};
  herr_t rc;
  H5E_BEGIN_TRY { rc = H5Dread(in.dset->id, type, mspace.id, fspace.id, H5P_DEFAULT, buf.data()); }
  H5E_END_TRY;
  if (rc < 0) fail("cannot read /runs of " + in.path + " (rows " + std::to_string(first) + "..): the file is damaged");
}

void reclaim(hid_t type, std::vector<unsigned char>& buf) {
  const hsize_t n = buf.size() / H5Tget_size(type);
  if (n == 0 || H5Tdetect_class(type, H5T_STRING) <= 0) return;
  Handle space{H5Screate_simple(1, &n, nullptr), H5Sclose};
  H5Dvlen_reclaim(type, space.id, H5P_DEFAULT, buf.data());
}

void check_inputs_belong_together(const std::vector<Input>& inputs) {
  const Input& first = inputs[0];
  for (std::size_t f = 0; f < inputs.size(); ++f) {
    const ShardOf& s = inputs[f].shard;
    const std::string& path = inputs[f].path;
    if (s.spec_hash != first.shard.spec_hash)
      fail(path + " comes from another spec than " + first.path + " (spec_hash differs)");
    if (s.inputs_hash.empty() || s.inputs_hash != first.shard.inputs_hash)
      fail(different_inputs(path, first.path, s.inputs_hash.empty()));
    if (s.count != first.shard.count)
      fail(path + " is shard " + s.shard + " but " + first.path + " has " + std::to_string(first.shard.count) +
           " shards");
    for (std::size_t g = 0; g < f; ++g) {
      std::error_code ec;
      if (fs::equivalent(path, inputs[g].path, ec)) fail(path + " is given twice (also as " + inputs[g].path + ")");
      if (s.shard == inputs[g].shard.shard)
        fail(path + " and " + inputs[g].path + " are both shard " + s.shard + " of the spec: give each shard once");
    }
    // What compare, table and figure need, so a merged file is one they read.
    check_result_columns(path);
  }
}

void check_same_columns(const std::vector<Input>& inputs) {
  for (std::size_t f = 1; f < inputs.size(); ++f)
    if (H5Tequal(inputs[f].ftype->id, inputs[0].ftype->id) <= 0)
      fail(inputs[f].path + " has other columns than " + inputs[0].path + " (written by another engine version)");
}

bool write_rows(hid_t dset, hid_t type, hsize_t first, hsize_t n, const void* buf) {
  Handle fspace{H5Dget_space(dset), H5Sclose};
  H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, &first, nullptr, &n, nullptr);
  Handle mspace{H5Screate_simple(1, &n, nullptr), H5Sclose};
  herr_t rc;
  H5E_BEGIN_TRY { rc = H5Dwrite(dset, type, mspace.id, fspace.id, H5P_DEFAULT, buf); }
  H5E_END_TRY;
  return rc >= 0;
}

std::string simd_targets(const std::vector<Input>& inputs) {
  std::string targets;
  for (const Input& in : inputs)
    if (has_attribute(in.path, "simd_target"))
      targets = join_name_lists(targets, read_attribute(in.path, "simd_target"));
  return targets;
}

void allow_open_files(std::size_t n) {
  rlimit lim{};
  if (getrlimit(RLIMIT_NOFILE, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY || lim.rlim_cur >= n + 64) return;
  lim.rlim_cur = std::min<rlim_t>(lim.rlim_max, n + 64);
  setrlimit(RLIMIT_NOFILE, &lim);
}

MergedFile::MergedFile(const std::string& path, hsize_t total, hid_t file_type) : path_(path) {
  Handle fapl{rollback_fapl(), H5Pclose};
  H5E_BEGIN_TRY { file_.id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id); }
  H5E_END_TRY;
  if (file_.id < 0) fail("cannot create " + path + ": " + rollback_open_error());
  hsize_t dims = total, maxdims = H5S_UNLIMITED, chunk = out_chunk_rows;
  Handle space{H5Screate_simple(1, &dims, &maxdims), H5Sclose};
  Handle dcpl{H5Pcreate(H5P_DATASET_CREATE), H5Pclose};
  H5Pset_chunk(dcpl.id, 1, &chunk);
  H5Pset_shuffle(dcpl.id);
  H5Pset_deflate(dcpl.id, out_deflate_level);
  dset_.id = H5Dcreate2(file_.id, "runs", file_type, space.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT);
  if (dset_.id < 0) fail("cannot create /runs in " + path);
}

void MergedFile::finish(const std::vector<Input>& inputs, std::set<std::string> skip,
                        const std::vector<Attribute>& extra) {
  skip.insert({"shard", "simd_target"});
  copy_attributes(inputs[0].path, file_.id, skip);
  std::string from;
  for (const Input& in : inputs) from += (from.empty() ? "" : "\n") + in.path;
  write_text_attribute(file_.id, "shard",
                       "merged from " + std::to_string(inputs.size()) + " files of " +
                           std::to_string(inputs[0].shard.count) + " shards");
  write_text_attribute(file_.id, "merged_from", from);
  write_text_attribute(file_.id, "merged_at", utc_now());
  if (const std::string targets = simd_targets(inputs); !targets.empty())
    write_text_attribute(file_.id, "simd_target", targets);
  for (const Attribute& a : extra) write_attribute(file_.id, a);
  H5Dclose(dset_.id);
  dset_.id = -1;
  const herr_t closed = close_quietly(file_.id);  // flushes: fails when the disk is full
  file_.id = -1;
  if (closed < 0) {
    roll_back(path_);
    fail_write(path_);
  }
}

void write_via_temp(const std::vector<Input>& inputs, const std::string& output,
                    const std::function<void(const std::string& temp)>& write) {
  const std::string temp = merge_temp_path(output);
  const fs::path parent = fs::path(output).parent_path();
  if (!parent.empty()) fs::create_directories(parent);
  // The merged file holds the shards' chunks, filtered alike: about the sum
  // of their sizes. A merge that cannot fit is not begun.
  std::uintmax_t bytes = 1u << 20;  // metadata
  for (const Input& in : inputs) {
    std::error_code size_ec;
    const std::uintmax_t size = fs::file_size(in.path, size_ec);
    if (!size_ec) bytes += size;
  }
  check_room(temp, bytes, "the merged file");
  try {
    write(temp);
  } catch (...) {
    std::error_code ec;
    fs::remove(temp, ec);
    fs::remove(journal_path(temp), ec);
    throw;
  }
  std::error_code ec;
  fs::remove(journal_path(output), ec);  // none of this file's: a stale one would mask it
  fs::rename(temp, output);
}

}  // namespace chaosweep::merge_detail
