#pragma once
// Seed 003's Tables 1-3, its complete-coverage loop and the mirror-mapping
// comparison, from the result rows of experiments/seed003.toml (parts
// labelled table1, table3, loop, mirror), beside the paper's numbers.
#include "analysis/result_set.hpp"
#include "analysis/text_table.hpp"

namespace chaosweep {

// Long format: table, row, quantity, ours, paper. Rows whose part is missing
// from the results are left out; none at all is an AnalysisError.
TextTable seed003_table(const ResultSet& rs);

}  // namespace chaosweep
