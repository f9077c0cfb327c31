#pragma once
// The HDF5 library's process-wide settings.

namespace chaosweep {

// Called first in main, before any other HDF5 call: the library then installs
// no exit handler. HDF5 1.10's shutdown crashes (SIGSEGV in H5F__close_cb) on
// a file whose close failed (a full disk, the file-size limit), so a sweep or
// merge that had cleaned up and meant to exit 3 died with 139. Every file is
// closed by its owner before exit, which leaves the handler nothing to do.
void skip_hdf5_exit_handler();

}  // namespace chaosweep
