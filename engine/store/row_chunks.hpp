#pragma once
// Rows of /runs as bytes, made off the writer's critical path: each piece of
// an append (rows up to a chunk boundary) is encoded on its own, so pieces
// can be encoded on many threads; a piece that is a whole chunk holding no
// variable-length text is also laid out as the file stores it, shuffled and
// deflated like the dataset's filters would, ready for H5Dwrite_chunk.
// Internal to the store's writer (h5_store.cpp).
#include <cstddef>
#include <deque>
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

struct EncodedPiece {
  std::size_t first = 0, count = 0;  // rows of the append
  std::deque<std::string> texts;     // variable-length strings buf points into, alive until written
  std::size_t text_bytes = 0;        // their size with the global heap's per-object overhead
  std::vector<unsigned char> chunk;  // the filtered chunk when the piece is one (else empty)
};

// Encodes rows [piece.first, +count) of `rows` into their slice of `buf`
// (memory layout, rows.size() * row_size bytes; the slice is zeroed first); with `make_chunk`
// (a whole chunk) and no variable-length text in it, also piece.chunk.
// Throws std::logic_error naming `file` when a value is wider than its
// fixed column. Safe to call for disjoint pieces at once.
void encode_piece(const std::vector<RunRow>& rows, const RowLayout& layout, bool make_chunk, const std::string& file,
                  unsigned char* buf, EncodedPiece& piece);

}  // namespace chaosweep
