// Compiled, never linked or run (tests/CMakeLists.txt builds it with
// test_engine): the store's public headers keep HDF5 and the spec parser to
// themselves. Were <hdf5.h> or engine/spec/sweep_spec.hpp reached from
// them, this file would not compile.
#include "engine/store/column_blocks.hpp"
#include "engine/store/disk_room.hpp"
#include "engine/store/h5_compare.hpp"
#include "engine/store/h5_library.hpp"
#include "engine/store/h5_merge.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/input_identity.hpp"
#include "engine/store/output_lock.hpp"
#include "engine/store/provenance.hpp"
#include "engine/store/rollback_driver.hpp"
#include "engine/store/slurm_dir.hpp"
#include "engine/store/stored_run.hpp"

#ifdef H5_VERS_MAJOR
#error "a public engine/store header includes <hdf5.h>"
#endif
