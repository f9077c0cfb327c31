// Compiled, never linked or run (tests/CMakeLists.txt builds it with
// test_engine): the row types and the HDF5 writer do not include the spec
// parser. Were engine/spec/sweep_spec.hpp reached from them, the definitions
// below would clash with its own and this file would not compile.
#include "engine/rows/json_writer.hpp"
#include "engine/rows/result_columns.hpp"
#include "engine/rows/run_row.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/rollback_driver.hpp"

namespace chaosweep {
struct SweepSpec {
  int not_the_parsers;
};
struct EnvironmentCache {
  int not_the_loaders;
};
}  // namespace chaosweep
