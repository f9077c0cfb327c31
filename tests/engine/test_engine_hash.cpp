// param_hash: the value in result files (and what --resume and compare rely
// on) must never change, whatever the code that computes it.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "engine/rows/run_hash.hpp"
#include "engine/spec/run_tuple.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {
namespace {

// The definition the files were written with: FNV-1a of "env=ENV;" and
// "NAME=%a;" for every parameter in table order, text built by snprintf;
// a parameter added since (not hashed_at_default) only when its bits differ
// from its default's.
std::int64_t reference_param_hash(const RunParams& p, const std::string& env) {
  std::string text = "env=" + env + ";";
  char buf[64];
  for (const ParamInfo& info : param_table()) {
    if (!info.hashed_at_default &&
        std::bit_cast<std::uint64_t>(info.get(p)) == std::bit_cast<std::uint64_t>(info.get(RunParams{})))
      continue;
    std::snprintf(buf, sizeof buf, "=%a;", info.get(p));
    text += std::string(info.name) + buf;
  }
  return std::int64_t(fnv1a64(text));
}

TEST(ParamHash, EqualsTheSnprintfDefinitionForEveryKindOfDouble) {
  const double specials[] = {0.0,
                             -0.0,
                             1.0,
                             -1.5,
                             0.1,
                             1e300,
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min() * 12345,
                             std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN(),
                             -std::numeric_limits<double>::quiet_NaN(),
                             std::bit_cast<double>(std::uint64_t(0x7ff0000000000001ULL)),  // a signalling NaN
                             std::ldexp(1.0, -1022) - std::ldexp(1.0, -1074),              // largest subnormal
                             std::ldexp(1.0, 1023),
                             std::ldexp(1.0, -1000),
                             1.0 + std::ldexp(1.0, -52)};
  const auto& table = param_table();
  RunParams p;
  for (double v : specials) {
    for (const ParamInfo& info : table) info.set(p, v);
    ASSERT_EQ(param_hash(p, "empty"), reference_param_hash(p, "empty")) << v;
  }
  // Random bit patterns (every exponent, sign and mantissa), one parameter
  // each, and random environment names.
  std::mt19937_64 rng(20);
  for (int k = 0; k < 20000; ++k) {
    RunParams q;
    for (const ParamInfo& info : table) info.set(q, std::bit_cast<double>(rng()));
    const std::string env = k % 3 ? "maps/m" + std::to_string(rng() % 1000) + ".txt" : "";
    ASSERT_EQ(param_hash(q, env), reference_param_hash(q, env)) << k;
  }
}

// param_hash resumes from the previous call's state at the first parameter
// that changed: runs that differ anywhere (one parameter, several, none, the
// environment, -0.0 for 0.0, one NaN for another) must still hash as defined.
TEST(ParamHash, ConsecutiveRunsThatShareParametersHashAsDefined) {
  const auto& table = param_table();
  std::mt19937_64 rng(21);
  RunParams q;
  std::string env = "empty";
  const double values[] = {
      0.0,    -0.0, 0.5, 0.25, std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::quiet_NaN(),
      1e-300, 3.0};
  for (int k = 0; k < 20000; ++k) {
    const int changes = int(rng() % 4);  // 0: the same run again
    for (int c = 0; c < changes; ++c) table[rng() % table.size()].set(q, values[rng() % std::size(values)]);
    if (rng() % 50 == 0) env = rng() % 2 ? "empty" : "maps/m" + std::to_string(rng() % 3) + ".txt";
    ASSERT_EQ(param_hash(q, env), reference_param_hash(q, env)) << k;
  }
}

// Hashes stored in result files by the engine before param_hash was
// rewritten (chaosweep sweep of the shipped specs, read with h5py).
TEST(ParamHash, MatchesTheHashesStoredInOlderResultFiles) {
  struct Stored {
    const char* spec;
    std::int64_t run_id, hash;
  };
  const Stored stored[] = {
      {"demo.toml", 0, 2785451249426810172LL},     {"demo.toml", 1, -7553346876704262540LL},
      {"demo.toml", 93, -540135775142728274LL},    {"demo.toml", 140, -8688268337617760349LL},
      {"demo.toml", 279, -4672858733000722818LL},  {"table1.toml", 0, 7065300603989322817LL},
      {"table1.toml", 1, 5297548751125384629LL},   {"table1.toml", 15, 7630708815750038722LL},
      {"table1.toml", 23, -5944372837708042184LL}, {"table1.toml", 46, 5761351595718064198LL},
  };
  EnvironmentCache cache;
  for (const Stored& s : stored) {
    const SweepSpec spec = load_sweep_spec(std::string(CHAOSWEEP_SOURCE_DIR) + "/experiments/" + s.spec);
    const RunTuple t = resolve_run(s.run_id, spec.run(s.run_id), cache);
    EXPECT_EQ(param_hash(t.params, t.env_spec), s.hash) << s.spec << " run " << s.run_id;
  }
}

}  // namespace
}  // namespace chaosweep
