#include "engine/store/h5_file_rows.hpp"

#include <algorithm>
#include <numeric>

#include "engine/store/h5_detail.hpp"

namespace chaosweep {

using h5::Handle;

FileRows file_rows_of(hid_t dset) {
  FileRows f;
  Handle dcpl{H5Dget_create_plist(dset), H5Pclose};
  if (H5Pget_layout(dcpl.id) == H5D_CHUNKED && H5Pget_chunk(dcpl.id, 1, &f.chunk_rows) != 1) f.chunk_rows = 0;
  unsigned flags = 0, level = 0;
  std::size_t nvalues = 1;
  if (H5Pget_nfilters(dcpl.id) == 2 &&
      H5Pget_filter2(dcpl.id, 0, &flags, nullptr, nullptr, 0, nullptr, nullptr) == H5Z_FILTER_SHUFFLE &&
      H5Pget_filter2(dcpl.id, 1, &flags, &nvalues, &level, 0, nullptr, nullptr) == H5Z_FILTER_DEFLATE && nvalues >= 1)
    f.deflate_level = int(level);
  Handle type{H5Dget_type(dset), H5Tclose};
  if (H5Tget_class(type.id) != H5T_COMPOUND) return f;
  const int n = H5Tget_nmembers(type.id);
  if (n <= 0) return f;
  f.offsets.assign(std::size_t(n), 0);
  f.variable_text.assign(std::size_t(n), false);
  // In the order of their offsets, as HDF5 moves them.
  std::vector<unsigned> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) {
    return H5Tget_member_offset(type.id, a) < H5Tget_member_offset(type.id, b);
  });
  std::size_t shift = 0;
  for (const unsigned i : order) {
    Handle mt{H5Tget_member_type(type.id, i), H5Tclose};
    const H5T_class_t cls = H5Tget_class(mt.id);
    const bool variable = cls == H5T_STRING && H5Tis_variable_str(mt.id) > 0;
    if (!variable && cls != H5T_INTEGER && cls != H5T_FLOAT && cls != H5T_STRING) {
      f.row_size = 0;
      return f;
    }
    f.offsets[i] = H5Tget_member_offset(type.id, i) + shift;
    f.variable_text[i] = variable;
    if (variable) shift += file_variable_text_size - H5Tget_size(mt.id);
  }
  f.row_size = H5Tget_size(type.id) + shift;
  return f;
}

}  // namespace chaosweep
