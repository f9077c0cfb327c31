#include "h5_merge.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include "cli_common.hpp"
#include "h5_store.hpp"
#include "input_identity.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error(what); }

// Every row of /runs as raw bytes in the file's own (native) row type.
struct RawRows {
  hid_t type = -1;  // memory type, owned
  std::size_t row_size = 0, id_offset = 0;
  std::vector<unsigned char> bytes;
  std::size_t count() const { return row_size ? bytes.size() / row_size : 0; }
  std::int64_t id(std::size_t i) const {
    std::int64_t v;
    std::memcpy(&v, bytes.data() + i * row_size + id_offset, 8);
    return v;
  }
  ~RawRows() {
    if (type >= 0) H5Tclose(type);
  }
};

// Reads /runs of `path`; a file that is missing, not HDF5, truncated or not a
// result file is refused naming it (count_rows checks all that, quietly).
void read_raw(const std::string& path, RawRows& out) {
  const hsize_t n = hsize_t(count_rows(path));
  herr_t rc = 0;
  hid_t file = -1, dset = -1;
  H5E_BEGIN_TRY {
    file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    dset = file >= 0 ? H5Dopen2(file, "/runs", H5P_DEFAULT) : -1;
  }
  H5E_END_TRY;
  if (dset < 0) {
    if (file >= 0) H5Fclose(file);
    fail("cannot open /runs of " + path);
  }
  hid_t ftype = H5Dget_type(dset);
  out.type = H5Tget_native_type(ftype, H5T_DIR_ASCEND);
  H5Tclose(ftype);
  out.row_size = H5Tget_size(out.type);
  const int idx = H5Tget_member_index(out.type, "run_id");
  if (idx < 0 || H5Tget_member_class(out.type, unsigned(idx)) != H5T_INTEGER) {
    H5Dclose(dset);
    H5Fclose(file);
    fail(path + ": /runs has no integer run_id column (not a chaosweep result file)");
  }
  out.id_offset = H5Tget_member_offset(out.type, unsigned(idx));
  out.bytes.resize(std::size_t(n) * out.row_size);
  H5E_BEGIN_TRY { rc = n ? H5Dread(dset, out.type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.bytes.data()) : 0; }
  H5E_END_TRY;
  H5Dclose(dset);
  H5Fclose(file);
  if (rc < 0) fail("cannot read /runs of " + path + ": the file is damaged");
}

std::vector<std::string> attribute_names(const std::string& path) {
  std::vector<std::string> names;
  hid_t file;
  H5E_BEGIN_TRY { file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT); }
  H5E_END_TRY;
  if (file < 0) return names;
  H5O_info_t info;
  H5Oget_info2(file, &info, H5O_INFO_NUM_ATTRS);
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    char buf[256];
    if (H5Aget_name_by_idx(file, ".", H5_INDEX_NAME, H5_ITER_INC, i, buf, sizeof buf, H5P_DEFAULT) > 0)
      names.push_back(buf);
  }
  H5Fclose(file);
  return names;
}

// A shard file's place in its sweep, from its provenance attributes.
struct ShardOf {
  std::string spec_hash, shard;  // shard as written: "K/N"
  std::string inputs_hash;       // "" when not recorded (an older chaosweep)
  int count = 1;
  std::int64_t runs_total = 0;
};

ShardOf shard_of(const std::string& path) {
  ShardOf s;
  s.spec_hash = read_attribute(path, "spec_hash");  // throws naming the file
  s.shard = read_attribute(path, "shard");
  try {
    s.inputs_hash = read_attribute(path, "inputs_hash");
  } catch (const std::exception&) {
  }
  const std::string total = read_attribute(path, "runs_total");
  int k = -1;
  char tail = 0;
  if (std::sscanf(s.shard.c_str(), "%d/%d%c", &k, &s.count, &tail) != 2 || k < 0 || s.count < 1 || k >= s.count)
    fail(path + ": attribute 'shard' is '" + s.shard +
         "', not K/N (a merged file cannot be merged again: give its shard files)");
  try {
    std::size_t used = 0;
    s.runs_total = std::stoll(total, &used);
    if (used != total.size() || s.runs_total < 0) throw std::invalid_argument(total);
  } catch (const std::exception&) {
    fail(path + ": attribute 'runs_total' is '" + total + "', not a run count");
  }
  return s;
}

// Why shard `path` cannot be merged with `first` though their spec is the
// same: the environment files differ (named), or `path` records none.
std::string different_inputs(const std::string& path, const std::string& first, bool unrecorded) {
  if (unrecorded)
    return path + " does not record its input files (written by an older chaosweep): whether its environment "
                  "files match " + first + "'s cannot be checked";
  const std::string changes = changed_inputs(read_attribute(first, "input_files"), read_attribute(path, "input_files"));
  return path + " was made with other input files than " + first + ": " +
         (changes.empty() ? "inputs_hash differs" : changes);
}

}  // namespace

std::string MergeReport::text() const {
  std::string s = std::to_string(rows) + " rows of " + std::to_string(runs_total) + " runs";
  auto list = [](const std::vector<std::int64_t>& v) {
    std::string t;
    for (std::size_t i = 0; i < std::min<std::size_t>(v.size(), 10); ++i) t += (i ? ", " : "") + std::to_string(v[i]);
    return t + (v.size() > 10 ? ", ..." : "");
  };
  if (!missing.empty()) {
    s += "\nmissing " + std::to_string(missing.size()) + " runs (run_id " + list(missing) + ")";
    std::string shards;
    for (int k : shards_to_rerun) shards += (shards.empty() ? "" : ",") + std::to_string(k);
    s += "\nre-run shards " + shards + " of " + std::to_string(shard_count) + " (e.g. chaosweep sweep SPEC -o OUT --shard " +
         std::to_string(shards_to_rerun.front()) + "/" + std::to_string(shard_count) + " --resume)";
  }
  if (!duplicated.empty()) s += "\nduplicated " + std::to_string(duplicated.size()) + " runs (run_id " + list(duplicated) + ")";
  return s;
}

MergeReport merge_results(const std::vector<std::string>& inputs, const std::string& output) {
  if (inputs.empty()) fail("no input files");
  MergeReport report;
  std::vector<ShardOf> shards;
  for (const std::string& in : inputs) {
    if (!fs::exists(in)) fail(in + " does not exist");
    shards.push_back(shard_of(in));
  }
  report.runs_total = shards[0].runs_total;
  report.shard_count = shards[0].count;
  std::vector<RawRows> parts(inputs.size());
  for (std::size_t f = 0; f < inputs.size(); ++f) {
    if (shards[f].spec_hash != shards[0].spec_hash)
      fail(inputs[f] + " comes from another spec than " + inputs[0] + " (spec_hash differs)");
    if (shards[f].inputs_hash.empty() || shards[f].inputs_hash != shards[0].inputs_hash)
      fail(different_inputs(inputs[f], inputs[0], shards[f].inputs_hash.empty()));
    if (shards[f].count != report.shard_count)
      fail(inputs[f] + " is shard " + shards[f].shard + " but " + inputs[0] + " has " +
           std::to_string(report.shard_count) + " shards");
    for (std::size_t g = 0; g < f; ++g) {
      std::error_code ec;
      if (fs::equivalent(inputs[f], inputs[g], ec))
        fail(inputs[f] + " is given twice (also as " + inputs[g] + ")");
      if (shards[f].shard == shards[g].shard)
        fail(inputs[f] + " and " + inputs[g] + " are both shard " + shards[f].shard +
             " of the spec: give each shard once");
    }
    read_raw(inputs[f], parts[f]);
    if (f > 0 && H5Tequal(parts[f].type, parts[0].type) <= 0)
      fail(inputs[f] + " has other columns than " + inputs[0] + " (written by another engine version)");
  }
  // Order every row by run_id; note holes and repeats.
  std::vector<std::pair<std::int64_t, std::pair<std::size_t, std::size_t>>> order;
  for (std::size_t f = 0; f < parts.size(); ++f)
    for (std::size_t i = 0; i < parts[f].count(); ++i) order.push_back({parts[f].id(i), {f, i}});
  std::sort(order.begin(), order.end());
  std::set<int> rerun;
  std::int64_t expect = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::int64_t id = order[k].first;
    if (k > 0 && id == order[k - 1].first) {
      report.duplicated.push_back(id);
      continue;
    }
    for (; expect < id; ++expect) report.missing.push_back(expect);
    expect = id + 1;
  }
  for (; expect < report.runs_total; ++expect) report.missing.push_back(expect);
  for (std::int64_t id : report.missing) rerun.insert(int(id % report.shard_count));
  report.shards_to_rerun.assign(rerun.begin(), rerun.end());
  report.rows = std::int64_t(order.size());
  if (!report.ok()) return report;

  const std::string partial = output + ".partial";
  const fs::path parent = fs::path(output).parent_path();
  if (!parent.empty()) fs::create_directories(parent);
  const std::size_t rs = parts[0].row_size;
  std::vector<unsigned char> out(order.size() * rs);
  for (std::size_t k = 0; k < order.size(); ++k)
    std::memcpy(out.data() + k * rs, parts[order[k].second.first].bytes.data() + order[k].second.second * rs, rs);
  hid_t file = H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) fail("cannot create " + partial);
  hsize_t dims = order.size(), maxdims = H5S_UNLIMITED, chunk = 1024;
  hid_t space = H5Screate_simple(1, &dims, &maxdims);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 1, &chunk);
  H5Pset_shuffle(dcpl);
  H5Pset_deflate(dcpl, 4);
  hid_t dset = H5Dcreate2(file, "runs", parts[0].type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  const herr_t rc = dims ? H5Dwrite(dset, parts[0].type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) : 0;
  H5Dclose(dset);
  H5Pclose(dcpl);
  H5Sclose(space);
  // Provenance: the first shard's, with the shard-specific entries replaced.
  for (const std::string& name : attribute_names(inputs[0])) {
    if (name == "shard") continue;
    write_text_attribute(file, name, read_attribute(inputs[0], name));
  }
  std::string from;
  for (const std::string& in : inputs) from += (from.empty() ? "" : "\n") + in;
  write_text_attribute(file, "shard", "merged from " + std::to_string(inputs.size()) + " files of " +
                                            std::to_string(report.shard_count) + " shards");
  write_text_attribute(file, "merged_from", from);
  write_text_attribute(file, "merged_at", utc_now());
  H5Fclose(file);
  if (rc < 0) fail("cannot write " + partial);
  fs::rename(partial, output);
  return report;
}

}  // namespace chaosweep
