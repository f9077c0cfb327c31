#pragma once
// Variable-length text of /runs read from the file's global heap here, not
// through HDF5's type conversion: a chunk holding such text could otherwise
// be read only by H5Dread, which unfilters it with HDF5's byte-at-a-time
// shuffle and converts every member (a third of a compare's time on rows
// with a message, issue 20). A chunk stores each string as 16 bytes: its
// length (4 bytes) and a global heap id (the collection's 8-byte address and
// the object's 4-byte index); the collection ("GCOL", HDF5 file format
// specification, "Global Heap") holds the bytes. Internal to the store's
// readers (column_blocks.cpp), like h5_file_rows.hpp.
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <list>
#include <string>
#include <unordered_map>
#include <vector>

namespace chaosweep {

class GlobalHeapText {
 public:
  // For `file`, opened by the rollback driver. usable() is false when its
  // heap cannot be read this way (a user block, addresses or lengths not of
  // 8 bytes): its readers go through HDF5.
  explicit GlobalHeapText(hid_t file);
  bool usable() const { return usable_; }

  // The string of a chunk's 16-byte element `e` (all zero: empty) into
  // `out`; false when the element or its collection is not as the format
  // says (the reader then asks HDF5, which names a damaged file).
  bool text(const unsigned char* e, std::string& out);

 private:
  struct Collection {
    std::uint64_t address = 0;
    std::vector<unsigned char> bytes;
    std::vector<std::pair<std::size_t, std::size_t>> objects;  // by index: offset in bytes, size (0, 0: none)
  };
  const Collection* collection(std::uint64_t address);
  bool load(std::uint64_t address, Collection& c) const;

  hid_t file_;
  bool usable_ = false;
  std::uint64_t base_ = 0;  // where address 0 is, for the driver (the user block's size)
  // Collections read, the last used first; bounded by their bytes.
  std::list<Collection> cache_;
  std::unordered_map<std::uint64_t, std::list<Collection>::iterator> index_;
  std::size_t cached_bytes_ = 0;
};

}  // namespace chaosweep
