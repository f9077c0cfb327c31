#include "engine/rows/run_hash.hpp"

#include <cstdio>

#include "kernels/core/param_table.hpp"

namespace chaosweep {

std::uint64_t fnv1a64(const std::string& bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::int64_t param_hash(const RunParams& p, const std::string& env) {
  std::string text = "env=" + env + ";";
  char buf[64];
  for (const ParamInfo& info : param_table()) {
    std::snprintf(buf, sizeof buf, "=%a;", info.get(p));
    text += std::string(info.name) + buf;
  }
  return std::int64_t(fnv1a64(text));
}

std::string hex64(std::uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)v);
  return buf;
}

}  // namespace chaosweep
