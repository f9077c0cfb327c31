#pragma once
// How wide the store makes the text columns a spec decides (env, label).
#include <cstddef>
#include <map>
#include <string>

#include "engine/spec/sweep_spec.hpp"

namespace chaosweep {

// Fixed storage (bytes incl. the NUL) for the text columns a spec decides,
// env and label: wide enough for the longest value any of its runs takes (a
// spec's file stays as compact as fixed-length text, which compresses to
// almost nothing, while variable-length text costs a heap object per row).
std::map<std::string, std::size_t> text_widths(const SweepSpec& spec);

}  // namespace chaosweep
