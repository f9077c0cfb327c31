#pragma once
// One description of every run parameter: its name (used by the CLI flags,
// sweep-spec keys, JSON fields and HDF5 columns alike), its meaning, and its
// allowed range. Pure data, so the kernels validate with the same bounds the
// engine reports to the user.
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kernels/core/run_params.hpp"

namespace chaosweep {

struct ParamInfo {
  enum class Kind { real, integer, choice };
  std::string_view name;
  std::string_view help;
  Kind kind;
  double lo, hi;                          // inclusive bounds (real, integer)
  bool may_be_unset;                      // NaN means "take the default from elsewhere"
  std::vector<std::string_view> choices;  // names of a choice's values, by index
  double (*get)(const RunParams&);        // a choice reads as its index
  void (*set)(RunParams&, double);
  // False for parameters added after result files began to store
  // param_hash: they enter the hash only when set away from their default,
  // so every earlier run keeps the hash its files hold.
  bool hashed_at_default = true;

  // Whether v is allowed: check's test, inline and without the message
  // (every run checks every parameter; the out-of-line call returning a
  // string cost 3% of a sweep of short runs).
  bool allows(double v) const {
    if (std::isnan(v)) return may_be_unset;
    if (kind == Kind::choice) return v >= 0 && v < double(choices.size()) && v == std::floor(v);
    return std::isfinite(v) && v >= lo && v <= hi && (kind != Kind::integer || v == std::floor(v));
  }
  // Empty when v is allowed, else a message naming the parameter and its range.
  std::string check(double v) const;
  std::string range_text() const;
  std::optional<double> choice_index(std::string_view value) const;
};

const std::vector<ParamInfo>& param_table();
const ParamInfo* find_param(std::string_view name);

// A number in its shortest round-trip form (std::to_chars): the fewest
// digits that read back as the same double ("0.3", "0.30000000000000004",
// "1e+06", "nan", "inf"). Every parameter chaosweep prints goes through it,
// so a printed value typed back in is the value that was used. With
// `significant` > 0, printf's %g of that many digits instead ("9.6" for
// 0.8 * 12, which reads back as 9.600000000000001): for messages that show
// computed positions, where the last bits are noise to the reader.
std::string format_number(double v, int significant = 0);

// First out-of-range parameter, as a message; empty when all are in range.
std::string check_ranges(const RunParams& p);

}  // namespace chaosweep
