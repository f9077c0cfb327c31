#pragma once
// Content hashes: of a run's parameters (to align runs across result files
// whatever their run_id) and of a spec's text (to tell whether shards belong
// to one sweep). FNV-1a, 64 bit.
#include <cstdint>
#include <string>

#include "kernels/core/run_params.hpp"

namespace chaosweep {

std::uint64_t fnv1a64(const std::string& bytes);
// Over the environment and every parameter (exact, as hex floats); not the
// label, which is a name, not an input of the run.
std::int64_t param_hash(const RunParams& p, const std::string& env);
std::string hex64(std::uint64_t v);

}  // namespace chaosweep
