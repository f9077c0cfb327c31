#include "engine/store/row_chunks.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "engine/rows/result_columns.hpp"
#include "engine/store/chunk_filters.hpp"

namespace chaosweep {

namespace {

// The file's bytes of `n` rows: numbers and fixed text as in memory; a
// variable-length string that is empty (a null pointer) as HDF5 stores it,
// a zero length and a null heap reference: all zeros.
void to_file_layout(const unsigned char* mem, std::size_t n, const RowLayout& l, unsigned char* out) {
  const auto& cols = result_columns();
  for (std::size_t r = 0; r < n; ++r) {
    const unsigned char* src = mem + r * l.row_size;
    unsigned char* dst = out + r * l.file_row_size;
    for (std::size_t i = 0; i < cols.size(); ++i) {
      if (cols[i].type == Column::Type::text && l.text_sizes[i] == 0) continue;  // zeros already
      const std::size_t size = cols[i].type == Column::Type::text ? l.text_sizes[i] : 8;
      std::memcpy(dst + l.file_offsets[i], src + l.offsets[i], size);
    }
  }
}

}  // namespace

void encode_rows(const std::vector<RunRow>& rows, const RowLayout& layout, const std::string& file, unsigned char* buf,
                 EncodedRows& part) {
  const auto& cols = result_columns();
  std::memset(buf + part.first * layout.row_size, 0, part.count * layout.row_size);
  for (std::size_t r = part.first; r < part.first + part.count; ++r) {
    unsigned char* base = buf + r * layout.row_size;
    for (std::size_t i = 0; i < cols.size(); ++i) {
      CellValue v = cols[i].get(rows[r]);
      unsigned char* dst = base + layout.offsets[i];
      if (const double* d = std::get_if<double>(&v)) {
        std::memcpy(dst, d, 8);
      } else if (const std::int64_t* n = std::get_if<std::int64_t>(&v)) {
        std::memcpy(dst, n, 8);
      } else if (layout.text_sizes[i] == 0) {
        // "" as a null pointer: HDF5 then stores no heap object, and the
        // row's reference is zeros, which compress away.
        std::string& text = std::get<std::string>(v);
        if (text.empty()) continue;
        part.texts.push_back(std::move(text));
        const char* p = part.texts.back().c_str();
        std::memcpy(dst, &p, sizeof p);
        part.text_bytes += part.texts.back().size() + 32;
      } else {
        const std::string& s = std::get<std::string>(v);
        // Widths are made to fit (the engine's words, text_widths(spec)): a
        // longer value is refused, never cut.
        if (s.size() >= layout.text_sizes[i])
          throw std::logic_error("column '" + cols[i].name + "' of " + file + " holds " +
                                 std::to_string(layout.text_sizes[i] - 1) + " bytes, but run " +
                                 std::to_string(rows[r].tuple.run_id) + " has " + std::to_string(s.size()) + ": '" + s +
                                 "'");
        std::memcpy(dst, s.data(), s.size());
      }
    }
  }
}

std::vector<unsigned char> file_chunk(const RowLayout& layout, const unsigned char* buf, std::size_t first,
                                      std::size_t count, std::size_t chunk_rows) {
  thread_local std::vector<unsigned char> raw;  // a chunk's worth, kept: no page faults per chunk
  raw.assign(chunk_rows * layout.file_row_size, 0);
  to_file_layout(buf + first * layout.row_size, count, layout, raw.data());
  return shuffled_and_deflated(raw.data(), raw.size(), layout.file_row_size, layout.deflate_level);
}

}  // namespace chaosweep
