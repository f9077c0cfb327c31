#include "engine/store/h5_library.hpp"

#include <hdf5.h>

namespace chaosweep {

void skip_hdf5_exit_handler() { H5dont_atexit(); }

}  // namespace chaosweep
