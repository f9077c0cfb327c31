#include "engine/rows/run_hash.hpp"

#include <bit>
#include <cstdio>
#include <vector>

#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

// FNV-1a fed byte by byte, so a hash needs no text built first.
struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  void add(char c) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  void add(std::string_view s) {
    for (char c : s) add(c);
  }
};

// The bytes glibc's printf("%a") writes for v ("0x1.8p+1", "-0x0p+0",
// "0x0.0000000000001p-1022", "inf", "-nan"), fed to the hash: files and
// --resume hold hashes of that text, so it must not change, and snprintf
// was the sweep's largest serial cost (tests/engine: ParamHash).
void add_hex_float(Fnv1a& f, double v) {
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(v);
  const bool negative = bits >> 63;
  const int biased = int((bits >> 52) & 0x7ff);
  std::uint64_t mantissa = bits & ((std::uint64_t(1) << 52) - 1);
  if (negative) f.add('-');
  if (biased == 0x7ff) {
    f.add(mantissa ? "nan" : "inf");
    return;
  }
  f.add("0x");
  f.add(biased == 0 ? '0' : '1');  // subnormals and zero: 0x0.
  if (mantissa) {
    f.add('.');
    int digits = 13;
    while ((mantissa & 0xf) == 0) {  // no trailing zero digits
      mantissa >>= 4;
      --digits;
    }
    for (int d = digits - 1; d >= 0; --d) f.add("0123456789abcdef"[(mantissa >> (4 * d)) & 0xf]);
  }
  const int exponent = biased == 0 ? (bits << 1 == 0 ? 0 : -1022) : biased - 1023;
  f.add('p');
  f.add(exponent < 0 ? '-' : '+');
  char digits[8];
  int n = 0;
  for (int e = exponent < 0 ? -exponent : exponent; n == 0 || e > 0; e /= 10) digits[n++] = char('0' + e % 10);
  while (n > 0) f.add(digits[--n]);
}

}  // namespace

std::uint64_t fnv1a64(const std::string& bytes) {
  Fnv1a f;
  f.add(bytes);
  return f.h;
}

// The hash of "env=ENV;" then "NAME=%a;" per parameter, in table order
// (a parameter not hashed_at_default only when it differs from its default).
// FNV-1a is a chain (each byte waits for the last), so a thread keeps its
// previous run's values and the state before each parameter: runs of one
// sweep differ in a few axes, and the hash resumes at the first parameter
// that changed (the table's ~40 planner-specific parameters precede A, B, C).
std::int64_t param_hash(const RunParams& p, const std::string& env) {
  struct Last {
    bool valid = false;
    std::string env;
    std::vector<std::uint64_t> bits;    // each parameter's value, as bits
    std::vector<std::uint64_t> before;  // FNV state before parameter i
  };
  thread_local Last last;
  const auto& table = param_table();
  static const std::vector<std::uint64_t> defaults = [&] {
    std::vector<std::uint64_t> d;
    for (const ParamInfo& info : table) d.push_back(std::bit_cast<std::uint64_t>(info.get(RunParams{})));
    return d;
  }();
  const std::size_t n = table.size();
  std::size_t from = 0;
  Fnv1a f;
  if (last.valid && last.env == env) {
    while (from < n && std::bit_cast<std::uint64_t>(table[from].get(p)) == last.bits[from]) ++from;
    if (from == n) {
      // Same parameters: the state after the last one is stored at n.
      return std::int64_t(last.before[n]);
    }
    f.h = last.before[from];
  } else {
    f.add("env=");
    f.add(env);
    f.add(';');
    last.env = env;
    last.bits.assign(n, 0);
    last.before.assign(n + 1, 0);
  }
  for (std::size_t i = from; i < n; ++i) {
    const double v = table[i].get(p);
    last.before[i] = f.h;
    last.bits[i] = std::bit_cast<std::uint64_t>(v);
    if (!table[i].hashed_at_default && last.bits[i] == defaults[i]) continue;
    f.add(table[i].name);
    f.add('=');
    add_hex_float(f, v);
    f.add(';');
  }
  last.before[n] = f.h;
  last.valid = true;
  return std::int64_t(f.h);
}

std::string hex64(std::uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)v);
  return buf;
}

}  // namespace chaosweep
