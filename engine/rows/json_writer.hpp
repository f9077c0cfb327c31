#pragma once
// One result row as a JSON object (all inputs and outputs; NaN as null).
#include <string>

#include "engine/rows/run_row.hpp"

namespace chaosweep {
std::string row_to_json(const RunRow& row, bool pretty = true);
std::string json_escape(const std::string& s);
}  // namespace chaosweep
