#pragma once
// Reading /runs a block of whole chunks at a time, only the columns a reader
// needs: memory is bounded by the block, not the file's rows, and HDF5
// converts only the members asked for (docs/store.md, "Readers").
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/rows/result_columns.hpp"
#include "engine/store/h5_store.hpp"

namespace chaosweep {

class ColumnBlockReader {
 public:
  // Opens `path` (as open_result_file) for `columns` of /runs. A block is
  // `block_rows` rounded up to whole chunks (0: 16 chunks). Throws
  // std::runtime_error naming the file, and listing its columns when one
  // asked for is not among them.
  ColumnBlockReader(const std::string& path, std::vector<std::string> columns, std::size_t block_rows = 0);
  ~ColumnBlockReader();
  ColumnBlockReader(const ColumnBlockReader&) = delete;
  ColumnBlockReader& operator=(const ColumnBlockReader&) = delete;

  std::size_t rows() const;        // of the file
  std::size_t block_rows() const;  // at most this many per block
  // The file's kind of column c (index into the columns given).
  Column::Type type(std::size_t c) const;
  // Reads the next block; false once every row has been read.
  bool next();
  std::size_t first() const;  // the current block's first row
  std::size_t size() const;   // and its number of rows
  // Column c's values in the current block, by the file's kind: integers
  // exact (i64), floats (f64), text. number(c) is any numeric column as
  // double (integers exact up to 2^53), as read_all_columns gives them.
  const std::vector<std::int64_t>& i64(std::size_t c) const;
  const std::vector<double>& f64(std::size_t c) const;
  const std::vector<std::string>& text(std::size_t c) const;
  const std::vector<double>& number(std::size_t c) const;
  // The blocks so far read through HDF5's type conversion (the slow path;
  // none in a file this engine wrote, text included).
  std::size_t blocks_converted() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The named columns of every row (a pass of blocks), each in its file's kind
// as read_typed_columns gives them, the others left out.
TypedColumns read_some_columns(const std::string& path, const std::vector<std::string>& columns);

}  // namespace chaosweep
