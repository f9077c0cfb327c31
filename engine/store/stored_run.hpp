#pragma once
// A stored result row, re-run: the run rebuilt from the row's own columns
// (every parameter of the parameter table, env, label, run_id: never from
// the spec, so it is the run that was stored, whatever the spec says now),
// and the re-run's row compared with the stored one, column by column, bit
// for bit. `run --from` and the trajectory/coverage figures use it.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/spec/run_tuple.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "engine/store/h5_store.hpp"

namespace chaosweep {

// One row's cells by column name.
struct StoredRow {
  std::map<std::string, double> numeric;         // floats; integers as double (exact up to 2^53)
  std::map<std::string, std::int64_t> integers;  // integer columns read exactly, where a caller has them
  std::map<std::string, std::string> text;
};

// Row r of `cols`.
StoredRow stored_row(const StoredColumns& cols, std::size_t r);

// The index of the row holding run_id `id` in a run_id column; throws
// SpecError starting with `where` (a file) when there is none, or more than one.
std::size_t row_of_run_id(const std::vector<double>& run_ids, std::int64_t id, const std::string& where);

// The run a row was made by. Throws SpecError naming a missing column or a
// value a parameter cannot take.
RunSpec run_spec_of(const StoredRow& row);

// Row `run_id` of result file `path` and its run, rebuilt (param_hash read
// exactly). Throws SpecError for a missing run_id or column, and the store's
// and the environment loader's errors, each naming the file.
struct StoredRun {
  StoredRow row;
  RunTuple tuple;
};
StoredRun load_stored_run(const std::string& path, std::int64_t run_id);

struct ColumnDifference {
  std::string column, stored, rerun;  // values in shortest round-trip form
};

struct RowComparison {
  std::vector<std::string> compared;          // the columns compared, in schema order
  std::vector<ColumnDifference> differences;  // those not bit-identical
};

// Compares every column of `stored` that the schema marks deterministic
// (all but wall_time) with `rerun`'s: doubles by their bits, integers
// exactly (through `integers` where given), text byte for byte.
RowComparison compare_row(const StoredRow& stored, const RunRow& rerun);

}  // namespace chaosweep
