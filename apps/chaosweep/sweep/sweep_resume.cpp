#include "apps/chaosweep/sweep/sweep_resume.hpp"

#include <filesystem>
#include <stdexcept>

#include "apps/chaosweep/cli_common.hpp"
#include "engine/spec/shard.hpp"
#include "engine/store/h5_store.hpp"

namespace chaosweep {

namespace {

std::string shard_text(Shard shard) { return std::to_string(shard.index) + "/" + std::to_string(shard.count); }

// The runs `partial` holds, which must be the shard's first ones (when
// `strided`: a sweep's, K, K + N, ...).
std::int64_t runs_to_skip(const std::string& partial, const SweepInputs& inputs, Shard shard, bool strided) {
  check_same_inputs(partial, inputs);
  if (read_attribute(partial, "shard") != shard_text(shard))
    throw std::runtime_error(partial + " holds shard " + read_attribute(partial, "shard") + ", not " +
                             shard_text(shard));
  const auto ids = read_i64_column(partial, "run_id");
  if (!strided) return std::int64_t(ids.size());
  for (std::size_t j = 0; j < ids.size(); ++j)
    if (ids[j] != shard_run_id(std::int64_t(j), shard.index, shard.count))
      throw std::runtime_error(partial + ": row " + std::to_string(j) + " has run_id " + std::to_string(ids[j]) +
                               ", not the shard's next run");
  return std::int64_t(ids.size());
}

}  // namespace

SweepStart start_sweep_output(const std::string& out, bool resume, bool force, const SweepInputs& inputs, Shard shard,
                              bool strided) {
  namespace fs = std::filesystem;
  const std::string partial = out + ".partial";
  SweepStart start;
  check_output_path(out, "-o");
  if (!resume) check_output_free(out, force, "-o", " (kept until this sweep completes), or --resume to keep it");
  start.lock = std::make_unique<OutputLock>(out);
  start.resuming = resume && fs::exists(partial);
  if (resume && !fs::exists(partial) && fs::exists(out)) {
    check_same_inputs(out, inputs);
    start.complete = true;
    return start;
  }
  if (!resume && !force && fs::exists(partial))
    throw std::runtime_error(partial +
                             " exists (an interrupted sweep): pass --resume to continue it, "
                             "or --force to start over");
  if (start.resuming) start.skip = runs_to_skip(partial, inputs, shard, strided);
  return start;
}

}  // namespace chaosweep
