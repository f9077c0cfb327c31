// libFuzzer target: any text given as a sweep spec either parses into a spec
// whose first and last runs can be built, or is refused with a SpecError.
// Anything else (a crash, another exception, a sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/spec/sweep_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // A directory that does not exist: `extends` must fail cleanly, not read files.
    const chaosweep::SweepSpec s = chaosweep::parse_sweep_spec(text, "fuzz.toml", "/nonexistent-fuzz-dir");
    const std::int64_t n = s.size();
    if (n > 0) {
      (void)s.run(0);
      (void)s.run(n - 1);
    }
  } catch (const chaosweep::SpecError&) {
  }
  return 0;
}
