#pragma once
// Result rows of varied values for the store's tests (writer, readers,
// merge): text columns of several values, some timed-out runs, and a message
// (variable-length text, which takes HDF5's own write path) every few rows.
#include <cstddef>
#include <string>
#include <vector>

#include "engine/rows/run_row.hpp"
#include "tests/support/kernel_test_util.hpp"

namespace chaosweep::test {

struct VariedRows {
  std::size_t message_every = 7;  // a message on the rows this many apart (0: none)
  std::size_t labels = 4;         // distinct labels, "case k"
  double shift = 0;               // added to the coverage time of the rows whose run_id % 11 == 3
  std::size_t repeat = 0;         // parameters recur (A from run_id % repeat); 0: every row its own
};

// Rows 0..n-1.
inline std::vector<RunRow> varied_rows(std::size_t n, const VariedRows& o = {}) {
  std::vector<RunRow> out(n);
  for (std::size_t j = 0; j < n; ++j) {
    RunRow& r = out[j];
    r.tuple.run_id = std::int64_t(j);
    r.tuple.env_spec = j % 3 ? "empty" : "maps/a.txt";
    r.tuple.label = "case " + std::to_string(j % o.labels);
    r.tuple.params = small_run(10);
    r.tuple.params.A = 0.3 + 1e-4 * double(o.repeat ? j % o.repeat : j);
    r.result.status = j % 5 ? Status::ok : Status::timeout;
    r.result.coverage_time = 100.0 + 0.5 * double(j % 97) + (j % 11 == 3 ? o.shift : 0.0);
    r.result.steps = std::int64_t(j * j);
    r.result.wall_time = 1e-3 * double(j);
    if (o.message_every && j % o.message_every == 0) r.result.message = "run " + std::to_string(j) + " said something";
  }
  return out;
}

}  // namespace chaosweep::test
