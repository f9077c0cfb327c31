#pragma once
// The columns of a result row, in output order: one schema shared by the HDF5
// store, `run --json` and the tests, so a field has one name everywhere.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "engine/rows/run_row.hpp"

namespace chaosweep {

using CellValue = std::variant<double, std::int64_t, std::string>;

struct Column {
  enum class Type { f64, i64, text };
  std::string name;
  Type type;
  // Storage of a text column: 0 for variable-length text (what users or
  // messages write: any length), else fixed bytes incl. the NUL for the
  // engine's own words (a choice, a status), sized to hold the longest.
  std::size_t text_size;
  std::function<CellValue(const RunRow&)> get;
  bool deterministic;  // false for wall-clock columns: not part of a run's pure result
};

const std::vector<Column>& result_columns();
const Column* find_column(const std::string& name);

}  // namespace chaosweep
