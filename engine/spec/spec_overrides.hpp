#pragma once
// `--set KEY=VALUE` on plan, sweep and slurm: a change of the spec's own text,
// so that the spec stored in a result file (and its spec_hash) is the spec
// that ran, re-parses to the same runs, and gets the spec's own errors.
//   KEY          a [fixed] setting or an [axes] axis of the spec file (an
//                axis when [axes] has it, else [fixed]); fixed.KEY, axes.KEY
//                say which; sweep.name, sweep.description
//   VALUE        a TOML value (4, 0.35, [1, 4], { start = 0.1, stop = 0.9,
//                num = 9 }, "text"), or a bare word taken as text (five_squares)
// A scalar given for an axis makes it an axis of that one value (run ids keep
// their meaning); a list or range given for a fixed setting makes it an axis,
// written last in [axes] (so it varies fastest).
#include <string>
#include <vector>

namespace chaosweep {

struct SpecOverride {
  std::string key, value;  // as given, around the first '='
  std::string text() const { return key + "=" + value; }
};

// Parses "KEY=VALUE"; throws SpecError naming --set and what is wrong.
SpecOverride parse_override(const std::string& arg);

// The spec text with every override applied, followed by a comment line that
// lists them. `source_name` is used in messages. Throws SpecError for a key
// the spec sets elsewhere ([[zip]], [[case]], [sample], [[part]]), a key given
// twice, or a value that is not TOML.
std::string apply_overrides(const std::string& text, const std::vector<SpecOverride>& overrides,
                            const std::string& source_name);

}  // namespace chaosweep
