// libFuzzer target: any text given as an environment file either parses into
// an environment with finite, in-map obstacles, or is refused with a
// std::runtime_error naming the file. Anything else is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "engine/spec/environment_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const chaosweep::Environment env = chaosweep::parse_environment(text, "fuzz.toml", 50, 50);
    if (!(env.lx > 0 && env.ly > 0 && std::isfinite(env.lx) && std::isfinite(env.ly))) std::abort();
    for (const chaosweep::Rect& r : env.obstacles)
      if (!(std::isfinite(r.x0) && std::isfinite(r.y0) && std::isfinite(r.x1) && std::isfinite(r.y1))) std::abort();
  } catch (const std::runtime_error&) {
  }
  return 0;
}
