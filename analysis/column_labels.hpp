#pragma once
// Axis labels for result columns: what a column means and its unit, so a
// figure's axes read "coverage time (s)" rather than "coverage_time".
#include <string>

namespace chaosweep {

// The label of a result column: the measured columns from a table here, the
// run parameters from their description in the parameter table (name and
// meaning, unit where it gives one); any other name as it is.
std::string axis_label(const std::string& column);

}  // namespace chaosweep
