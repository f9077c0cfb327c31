#pragma once
// The values of a sweep range ({start, stop, step} or {start, stop, num}) as
// the decimals a person means by it. A spec's 0.2 and 0.05 are read as the
// decimals 0.2 and 0.05 (the shortest digits that round-trip the doubles
// TOML gave), the range is computed in scaled integers at their precision,
// and each value is the double nearest the exact result: {0.2, 0.4, 0.05}
// gives 0.3, never 0.30000000000000004, so a value printed in its shortest
// form and typed back (`run --C 0.3`, `--where C=0.3`) is the stored one.
//
// {step}: start + k step, k = 0, 1, ... while not past stop (stop is in the
//   range exactly when it lies on the decimal grid).
// {num}: start + (stop - start) i / (num - 1). Both ends are start and stop
//   exactly; each interior value is the double nearest the exact quotient,
//   so it is the decimal itself when the spacing is a finite decimal
//   ({0.35, 0.65, num 7} gives 0.4, 0.45, ...), and otherwise the closest a
//   double can be (0.051 + 0.9/31 is 0.08003225806451612).
//
// Numbers too large or too finely divided for 128-bit scaled integers
// (beyond about 28 significant digits between start, stop and step, or past
// 1e-40 in precision) fall back to the floating-point formulas above.
#include <cstdint>
#include <vector>

namespace chaosweep {

__extension__ typedef __int128 decimal_int;  // GCC's and clang's 128-bit integer

class DecimalRange {
 public:
  // Callers check that step is finite, non-zero and points from start to
  // stop, and that num >= 1 (num == 1 needs start == stop).
  static DecimalRange by_step(double start, double stop, double step);
  static DecimalRange by_count(double start, double stop, std::int64_t num);

  // How many values (a double: an absurd range can exceed any integer type;
  // callers bound it before calling at()).
  double count() const { return count_; }
  double at(std::int64_t k) const;  // 0 <= k < count()
  std::vector<double> values() const;
  bool exact() const { return exact_; }  // false: the floating-point fallback

 private:
  double start_ = 0, stop_ = 0, step_ = 0, count_ = 0;
  bool by_count_ = false, exact_ = false;
  int exponent_ = 0;                   // values are integers times 10^exponent_
  decimal_int s_ = 0, t_ = 0, p_ = 0;  // start, stop, step scaled by 10^-exponent_
};

}  // namespace chaosweep
