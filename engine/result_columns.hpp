#pragma once
// The columns of a result row, in output order: one schema shared by the HDF5
// store, `run --json` and the tests, so a field has one name everywhere.
#include <cstdint>
#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "run_tuple.hpp"

namespace chaosweep {

using CellValue = std::variant<double, std::int64_t, std::string>;

struct Column {
  enum class Type { f64, i64, text };
  std::string name;
  Type type;
  std::size_t text_size;  // fixed storage for text columns, bytes incl. NUL
  std::function<CellValue(const RunRow&)> get;
  bool deterministic;     // false for wall-clock columns: not part of a run's pure result
};

const std::vector<Column>& result_columns();
const Column* find_column(const std::string& name);

}  // namespace chaosweep
