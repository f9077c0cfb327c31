#pragma once
// HDF5's shuffle and deflate filters, run off the library so whole chunks can
// be made and unmade on many threads (the sweep's writer, merge), with the
// very bytes HDF5's own filter pipeline makes and reads.
#include <cstddef>
#include <vector>

namespace chaosweep {

// out[c * rows + r] = in[r * cols + c]: a rows x cols matrix of bytes
// transposed. Unshuffling only the bytes of some members of a shuffled chunk
// of n elements is this on the rows of those bytes (rows = their size, cols = n).
void transpose_bytes(const unsigned char* in, std::size_t rows, std::size_t cols, unsigned char* out);

// Shuffle: byte j of element i goes to j * n + i (n = in.size() / element).
// With deflated(), the filters by their definitions: what the tests hold
// shuffled_and_deflated() to.
std::vector<unsigned char> shuffled(const std::vector<unsigned char>& in, std::size_t element);
// Its inverse: `size` bytes of `in` back into `out` (as many).
void unshuffle(const unsigned char* in, std::size_t size, std::size_t element, unsigned char* out);

// Deflate: compress2 at `level` (zlib format, as H5Z_FILTER_DEFLATE stores).
std::vector<unsigned char> deflated(const std::vector<unsigned char>& in, int level);
// Both filters on one chunk of `size` bytes of elements of `element` bytes
// (the bytes of deflated(shuffled(...))), with a scratch buffer and a zlib
// stream kept per thread: a fresh chunk-sized buffer and zlib's 256 KB of
// state per chunk were page faults, taken under the process's memory lock,
// that held the sweep's threads up one another.
std::vector<unsigned char> shuffled_and_deflated(const unsigned char* in, std::size_t size, std::size_t element,
                                                 int level);
// Inflates `n` bytes of `in` into exactly `out_size` bytes of `out`; false
// when they are not a zlib stream of that size (a damaged chunk).
bool inflate_exactly(const unsigned char* in, std::size_t n, unsigned char* out, std::size_t out_size);

}  // namespace chaosweep
