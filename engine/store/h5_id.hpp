#pragma once
// An HDF5 object id (hid_t) as the store's public headers pass it: an opaque
// integer, so that their includers need not see <hdf5.h>. The store's own
// sources check that it is hid_t (h5_detail.hpp).
#include <cstdint>

namespace chaosweep {
using H5Id = std::int64_t;
}  // namespace chaosweep
