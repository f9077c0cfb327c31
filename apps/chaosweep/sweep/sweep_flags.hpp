#pragma once
// The flags of `chaosweep sweep`, as parsed.
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace chaosweep {

struct SweepFlags {
  std::string spec, out, shard, progress = "auto";
  std::vector<std::string> sets;  // --set KEY=VALUE
  int threads = 0;
  std::int64_t batch = 4096;
  double flush_seconds = 10;
  bool quiet = false, resume = false, force = false;
};

// Declares the flags on `cmd`, parsed into `flags` (which must outlive it).
void add_sweep_flags(CLI::App& cmd, SweepFlags& flags);

}  // namespace chaosweep
