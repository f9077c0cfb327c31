#include "engine/store/chunk_filters.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace chaosweep {

namespace {

// Byte (r, c) of 8 rows of 8 bytes (a[r], byte c its c-th lowest) to (c, r):
// the off-diagonal halves swapped, then their quarters, then their bytes.
void transpose8(std::uint64_t a[8]) {
  constexpr std::uint64_t mask[3] = {0x00000000FFFFFFFFull, 0x0000FFFF0000FFFFull, 0x00FF00FF00FF00FFull};
  for (int level = 0, d = 4; level < 3; ++level, d /= 2)
    for (int r = 0; r < 8; ++r) {
      if (r & d) continue;
      const int bits = 8 * d;
      const std::uint64_t t = ((a[r] >> bits) ^ a[r + d]) & mask[level];
      a[r] ^= t << bits;
      a[r + d] ^= t;
    }
}

}  // namespace

// Tiles of 8 x 8 bytes as 64-bit words (a byte at a time spent ~10% of a
// merge), 64 columns of tiles at a time so the rows written stay in cache;
// the edges a byte at a time.
void transpose_bytes(const unsigned char* in, std::size_t rows, std::size_t cols, unsigned char* out) {
  const std::size_t rows8 = std::endian::native == std::endian::little ? rows / 8 * 8 : 0, cols8 = cols / 8 * 8;
  for (std::size_t c_block = 0; c_block < cols8; c_block += 64) {
    const std::size_t c_end = std::min(cols8, c_block + 64);
    for (std::size_t r0 = 0; r0 < rows8; r0 += 8)
      for (std::size_t c0 = c_block; c0 < c_end; c0 += 8) {
        std::uint64_t a[8];
        for (std::size_t k = 0; k < 8; ++k) std::memcpy(&a[k], in + (r0 + k) * cols + c0, 8);
        transpose8(a);
        for (std::size_t k = 0; k < 8; ++k) std::memcpy(out + (c0 + k) * rows + r0, &a[k], 8);
      }
  }
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = r < rows8 ? cols8 : 0; c < cols; ++c) out[c * rows + r] = in[r * cols + c];
}

std::vector<unsigned char> shuffled(const std::vector<unsigned char>& in, std::size_t element) {
  std::vector<unsigned char> out(in.size());
  transpose_bytes(in.data(), in.size() / element, element, out.data());
  return out;
}

void unshuffle(const unsigned char* in, std::size_t size, std::size_t element, unsigned char* out) {
  transpose_bytes(in, element, size / element, out);
}

std::vector<unsigned char> deflated(const std::vector<unsigned char>& in, int level) {
  uLongf size = compressBound(uLong(in.size()));
  std::vector<unsigned char> out(size);
  if (compress2(out.data(), &size, in.data(), uLong(in.size()), level) != Z_OK)
    throw std::runtime_error("zlib: cannot compress a chunk of rows");
  out.resize(size);
  return out;
}

namespace {

// A deflate stream reset for each chunk instead of set up anew.
struct Deflater {
  z_stream z{};
  int level = -1;  // none set up yet
  ~Deflater() {
    if (level >= 0) deflateEnd(&z);
  }
  z_stream& reset(int want) {
    if (level == want) {
      if (deflateReset(&z) != Z_OK) throw std::runtime_error("zlib: cannot reset a deflate stream");
      return z;
    }
    if (level >= 0) deflateEnd(&z);
    level = -1;
    z = z_stream{};
    if (deflateInit(&z, want) != Z_OK) throw std::runtime_error("zlib: cannot set up a deflate stream");
    level = want;
    return z;
  }
};

}  // namespace

std::vector<unsigned char> shuffled_and_deflated(const unsigned char* in, std::size_t size, std::size_t element,
                                                 int level) {
  thread_local std::vector<unsigned char> shuffled_bytes, packed;
  thread_local Deflater deflater;
  shuffled_bytes.resize(size);
  transpose_bytes(in, size / element, element, shuffled_bytes.data());
  z_stream& z = deflater.reset(level);
  if (size > std::numeric_limits<uInt>::max()) throw std::runtime_error("zlib: a chunk of rows is too large");
  packed.resize(deflateBound(&z, uLong(size)));
  z.next_in = shuffled_bytes.data();
  z.avail_in = uInt(size);
  z.next_out = packed.data();
  z.avail_out = uInt(packed.size());
  if (deflate(&z, Z_FINISH) != Z_STREAM_END) throw std::runtime_error("zlib: cannot compress a chunk of rows");
  return {packed.begin(), packed.begin() + std::ptrdiff_t(z.total_out)};
}

bool inflate_exactly(const unsigned char* in, std::size_t n, unsigned char* out, std::size_t out_size) {
  if (n > std::numeric_limits<uLong>::max() || out_size > std::numeric_limits<uLongf>::max()) return false;
  uLongf size = uLongf(out_size);
  return uncompress(out, &size, in, uLong(n)) == Z_OK && size == out_size;
}

}  // namespace chaosweep
