#pragma once
// The root attributes of a sweep's result file (docs/store.md).
#include <string>
#include <vector>

#include "apps/chaosweep/sweep/sweep_shard.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/input_identity.hpp"

namespace chaosweep {

// All of them for a new file; for a resumed one (`resumed` names it) when
// and where it went on, with every SIMD target the file's rows were
// computed with.
std::vector<Attribute> sweep_provenance(const SweepSpec& spec, const SweepInputs& inputs, const std::string& spec_path,
                                        Shard shard, int threads, const std::string& target,
                                        const std::string& resumed);

}  // namespace chaosweep
