#pragma once
// How a result file lays out /runs rows in its chunks, read off the dataset:
// what the writer and merge need to make or unmake chunks themselves.
// Internal to the store (h5_store.cpp, h5_merge.cpp), like h5_detail.hpp.
#include <hdf5.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace chaosweep {

// A variable-length string in a chunk: its length (4 bytes) and a global
// heap id (an 8-byte collection address and a 4-byte index); all zero for
// an empty (or null) string, which has no heap object.
inline constexpr std::size_t file_variable_text_size = 16;
inline bool empty_variable_text(const unsigned char* e) {
  return std::all_of(e, e + file_variable_text_size, [](unsigned char b) { return b == 0; });
}

struct FileRows {
  std::size_t row_size = 0;          // bytes of a row in a chunk; 0: a member of another kind
  std::vector<std::size_t> offsets;  // per member (in member order), in a chunk's row
  std::vector<bool> variable_text;   // per member: a variable-length string (16 bytes, 0 when empty)
  int deflate_level = -1;            // the filters are shuffle then deflate at this level; else -1
  hsize_t chunk_rows = 0;            // rows per chunk (0: not chunked)
};

// H5Dget_type gives the row type as read into memory (a variable-length
// string as a char*); in the file such a string is 16 bytes (a length and a
// global heap id of 8-byte addresses, the default), and HDF5 moves the
// members after it by the difference (H5T__set_loc). Members may be numbers
// and strings only. tests/engine: StoreChunks pins this against HDF5's own chunks.
FileRows file_rows_of(hid_t dset);

}  // namespace chaosweep
