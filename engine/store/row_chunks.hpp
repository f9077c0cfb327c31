#pragma once
// Rows of /runs as bytes, made off the writer's critical path: an append's
// rows are encoded in blocks on many threads, and each whole chunk of them
// holding no variable-length text is laid out as the file stores it,
// shuffled and deflated like the dataset's filters would, ready for
// H5Dwrite_chunk.
// Internal to the store's writer (h5_store.cpp).
#include <cstddef>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "engine/rows/run_row.hpp"

namespace chaosweep {

// Where each column sits in a row, in memory (what H5Dwrite converts) and in
// the file (what a raw chunk holds).
struct RowLayout {
  std::size_t row_size = 0;               // memory
  std::vector<std::size_t> offsets;       // memory, per column
  std::vector<std::size_t> text_sizes;    // per column: 0 variable-length, else fixed bytes
  std::size_t file_row_size = 0;          // 0: raw chunks cannot be made (an unexpected file type)
  std::vector<std::size_t> file_offsets;  // per column
  int deflate_level = 4;                  // the dataset's filter (shuffle, then deflate)
};

// Rows [first, first + count) of an append, encoded into their slice of the
// append's buffer.
struct EncodedRows {
  std::size_t first = 0, count = 0;
  std::deque<std::string> texts;  // variable-length strings the buffer points into, alive until written
  std::size_t text_bytes = 0;     // their size with the global heap's per-object overhead
};

// Encodes rows [part.first, +count) of `rows` into their slice of `buf`
// (memory layout, rows.size() * row_size bytes; the slice is zeroed first).
// Throws std::logic_error naming `file` when a value is wider than its
// fixed column. Safe to call for disjoint parts at once: an append's rows
// go in blocks much smaller than a chunk, so that a batch's few chunks do
// not leave threads idle.
void encode_rows(const std::vector<RunRow>& rows, const RowLayout& layout, const std::string& file, unsigned char* buf,
                 EncodedRows& part);

// An append's rows made ready to write (H5RunWriter::prepare): encoded, each
// piece that starts a chunk and holds no variable-length text filtered.
// Owns all that the write reads (the buffer, the strings it points to), so
// the rows it came from may be overwritten before it is written.
struct PreparedRows {
  struct Piece {
    std::size_t first, count, parts_end;  // its blocks: parts[previous piece's parts_end, parts_end)
    std::vector<unsigned char> chunk;     // the filtered chunk when the piece is one (else empty)
  };
  std::size_t first_row = 0, n = 0;  // they follow the file's first_row rows
  std::vector<Piece> pieces;         // split at the file's chunk boundaries
  std::vector<EncodedRows> parts;
  std::unique_ptr<unsigned char[]> buf;  // n rows in memory layout
  std::size_t buf_size = 0;
  std::size_t text_bytes = 0;
};

// The chunk of rows [first, first + count) of `buf` (encoded, holding no
// variable-length text) as the file stores it: laid out, shuffled and
// deflated, `chunk_rows` rows long (rows past `count` zeros, as HDF5 fills
// the end of the dataset's last chunk). Safe to call for disjoint chunks at
// once.
std::vector<unsigned char> file_chunk(const RowLayout& layout, const unsigned char* buf, std::size_t first,
                                      std::size_t count, std::size_t chunk_rows);

}  // namespace chaosweep
