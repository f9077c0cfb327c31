#include "apps/chaosweep/sweep/sweep_provenance.hpp"

#include <cstdlib>
#include <filesystem>

#include "engine/store/provenance.hpp"
#include "engine/store/version.hpp"

namespace chaosweep {

std::vector<Attribute> sweep_provenance(const SweepSpec& spec, const SweepInputs& inputs, const std::string& spec_path,
                                        Shard shard, int threads, const std::string& target,
                                        const std::string& resumed) {
  std::vector<Attribute> a;
  std::string targets = target;
  if (resumed.empty()) {
    a = {{"engine_version", std::string(engine_version())},
         {"git_commit", std::string(git_commit())},
         {"git_dirty", git_dirty()},
         {"spec", spec.text},
         {"spec_hash", inputs.spec_hash},
         {"inputs_hash", inputs.hash()},
         {"input_files", inputs.text()},
         // Absolute: a file read elsewhere (another directory, a notebook) still names its spec.
         {"spec_path", std::filesystem::absolute(spec_path).lexically_normal().string()},
         {"spec_name", spec.name},
         {"runs_total", std::int64_t(spec.size())},
         {"shard", std::to_string(shard.index) + "/" + std::to_string(shard.count)},
         {"start_time", utc_now()}};
  } else {
    a = {{"resumed_at", utc_now()}};
    if (has_attribute(resumed, "simd_target"))
      targets = join_name_lists(read_attribute(resumed, "simd_target"), target);
  }
  a.push_back({"host", host_name()});
  a.push_back({"threads", std::int64_t(threads)});
  a.push_back({"simd_target", targets});
  for (const char* v : {"SLURM_JOB_ID", "SLURM_ARRAY_JOB_ID", "SLURM_ARRAY_TASK_ID"})
    if (const char* val = std::getenv(v)) a.push_back({v, std::string(val)});
  return a;
}

}  // namespace chaosweep
