#pragma once
// `chaosweep table readings`: Table 1 rows of seed 000 run under several
// readings of the paper's text (obstacle response, transit clock and
// re-plan, zone goal and order, coverage of obstacle cells, layout), each
// row's coverage times beside the paper's, and each obstacle row's ratio to
// the open-map row of the same case beside the paper's ratio.
#include "analysis/result_set.hpp"
#include "analysis/tables.hpp"
#include "analysis/text_table.hpp"

namespace chaosweep {

// Groups by the reading columns (opt.by, else those of the list below that
// vary over the runs), then by row (label) and env. opt.paper: the paper's
// Table 1 (experiments/table1_paper.csv).
TextTable table1_readings(const ResultSet& rs, const TableOptions& opt);

// The run parameters a reading may set (the default reading columns).
const std::vector<std::string>& reading_columns();

}  // namespace chaosweep
