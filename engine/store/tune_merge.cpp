#include "engine/store/tune_merge.hpp"

#include <algorithm>

#include "engine/store/h5_store.hpp"

namespace chaosweep::merge_detail {

void check_tune_shard_finished(const Input& in) {
  if (!has_attribute(in.path, "end_time") || std::int64_t(in.rows) != in.shard.runs_total)
    fail(in.path + " is not a finished tune (" + std::to_string(in.rows) + " rows, runs_total " +
         std::to_string(in.shard.runs_total) + ", " + (has_attribute(in.path, "end_time") ? "" : "no ") +
         "end_time): finish it with chaosweep tune SPEC -o OUT --shard " + in.shard.shard + " --resume");
}

namespace {

// Every input's rows after the one before's, `block` rows at a time,
// through HDF5's conversion (variable-length text is read and written as
// strings; a tune's files are small beside a sweep's).
void write_concatenated(const std::vector<const Input*>& by_index, hid_t dset, hid_t type, hsize_t block,
                        const std::string& path) {
  std::vector<unsigned char> buf;
  struct Reclaim {  // the strings HDF5 allocated, freed also when a write fails
    hid_t type;
    std::vector<unsigned char>& buf;
    ~Reclaim() { reclaim(type, buf); }
  } reclaim_buf{type, buf};
  hsize_t at = 0;
  for (const Input* in : by_index)
    for (hsize_t first = 0; first < in->rows; first += block) {
      const hsize_t n = std::min(block, in->rows - first);
      read_rows(*in, first, n, buf, type);
      const bool written = write_rows(dset, type, at, n, buf.data());
      reclaim(type, buf);
      buf.clear();
      if (!written) fail_write(path);
      at += n;
    }
}

}  // namespace

MergeReport merge_tune_inputs(std::vector<Input>& inputs, const std::string& output, const MergeOptions& options) {
  check_inputs_belong_together(inputs);
  MergeReport report;
  report.tune = true;
  report.shard_count = inputs[0].shard.count;
  allow_open_files(inputs.size());
  for (Input& in : inputs) {
    open_input(in, 0);
    check_tune_shard_finished(in);
    report.rows += std::int64_t(in.rows);
  }
  check_same_columns(inputs);
  // A shard validated beside a grid's best holds config_id 0 rows of that grid.
  const auto grid = [](const Input& in) {
    return has_attribute(in.path, "tune_grid") ? read_attribute(in.path, "tune_grid") : std::string();
  };
  for (const Input& in : inputs)
    if (grid(in) != grid(inputs[0]))
      fail(in.path + " was validated beside " + (grid(in).empty() ? "no grid" : "grid " + grid(in)) + ", " +
           inputs[0].path + " beside " + (grid(inputs[0]).empty() ? "none" : grid(inputs[0])) +
           ": run every shard with the same --grid");
  std::vector<const Input*> by_index(std::size_t(report.shard_count), nullptr);
  for (const Input& in : inputs) by_index[std::size_t(in.shard.index)] = &in;
  for (int k = 0; k < report.shard_count; ++k)
    if (!by_index[std::size_t(k)]) report.shards_to_rerun.push_back(k);
  report.missing = std::int64_t(report.shards_to_rerun.size());
  report.runs_total = report.rows;
  if (!report.ok()) return report;
  const hid_t type = inputs[0].native->id;
  const hsize_t block =
      std::clamp<hsize_t>(options.block_bytes / std::max<std::size_t>(H5Tget_size(type), 1), 1, hsize_t(1) << 16);
  write_via_temp(inputs, output, [&](const std::string& temp) {
    MergedFile out(temp, hsize_t(report.rows), inputs[0].ftype->id);
    write_concatenated(by_index, out.runs(), type, block, temp);
    out.finish(inputs, {"runs_total"}, {{"runs_total", report.rows}});
  });
  return report;
}

}  // namespace chaosweep::merge_detail

namespace chaosweep {

std::string check_tune_shard_file(const std::string& path, int index, int count) {
  merge_detail::Input in;
  in.path = path;
  in.shard = merge_detail::shard_of(path);
  const std::string want = std::to_string(index) + "/" + std::to_string(count);
  if (in.shard.kind != "tune") merge_detail::fail(path + " is not a tune's file (of a sweep?)");
  if (in.shard.shard != want)
    merge_detail::fail(path + " is shard " + in.shard.shard + ", not " + want + " (of another tune)");
  merge_detail::open_input(in, 0);
  merge_detail::check_tune_shard_finished(in);
  check_result_columns(path);
  return in.shard.spec_hash + "\t" + in.shard.inputs_hash;
}

}  // namespace chaosweep
