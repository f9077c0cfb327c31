#include "engine/store/column_blocks.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "engine/store/chunk_filters.hpp"
#include "engine/store/global_heap_text.hpp"
#include "engine/store/h5_detail.hpp"
#include "engine/store/h5_file_rows.hpp"

namespace chaosweep {

using h5::Handle;
using h5::input_fail;

// Named, not anonymous: ColumnBlockReader::Impl (external linkage) holds
// them (-Wsubobject-linkage).
namespace column_blocks_detail {

// A column asked for, as it sits in the packed memory row HDF5 fills.
struct Wanted {
  std::string name;
  std::size_t offset = 0, size = 0;
  H5T_class_t cls = H5T_NO_CLASS;
  bool is_signed = false, variable = false;
  std::size_t file_offset = 0;  // in a chunk's row (FileRows)
  std::vector<std::int64_t> i64;
  std::vector<double> f64;  // floats, or integers as double
  std::vector<std::string> text;
};

}  // namespace column_blocks_detail

using column_blocks_detail::Wanted;

namespace {

constexpr hsize_t default_chunks_per_block = 16;

// Empties w's values for a block of `n` rows.
void prepare(Wanted& w, std::size_t n) {
  w.i64.clear();
  w.f64.clear();
  w.text.clear();
  if (w.cls == H5T_STRING) {
    w.text.reserve(n);
  } else {
    w.f64.resize(n);
    if (w.cls == H5T_INTEGER) w.i64.resize(n);
  }
}

// Row r's value of w from `p`, its bytes as the native type holds them (a
// variable-length string as a char*); text is appended, so rows come in order.
void take(Wanted& w, std::size_t r, const unsigned char* p) {
  if (w.cls == H5T_STRING) {
    if (w.variable) {
      const char* s;
      std::memcpy(&s, p, sizeof s);
      w.text.emplace_back(s ? s : "");
    } else {
      const char* s = reinterpret_cast<const char*>(p);
      w.text.emplace_back(s, strnlen(s, w.size));
    }
  } else if (w.cls == H5T_INTEGER) {
    std::int64_t i;
    double d;
    if (w.size == 8) {
      std::memcpy(&i, p, 8);
      d = w.is_signed ? double(i) : double(std::uint64_t(i));
    } else {
      std::int32_t k;
      std::memcpy(&k, p, 4);
      i = w.is_signed ? std::int64_t(k) : std::int64_t(std::uint32_t(k));
      d = double(i);
    }
    w.i64[r] = i;
    w.f64[r] = d;
  } else if (w.size == 8) {
    std::memcpy(&w.f64[r], p, 8);
  } else {
    float f;
    std::memcpy(&f, p, 4);
    w.f64[r] = f;
  }
}

}  // namespace

struct ColumnBlockReader::Impl {
  std::string path;
  Handle file{-1, H5Fclose}, dset{-1, H5Dclose}, mem{-1, H5Tclose}, fspace{-1, H5Sclose}, dxpl{-1, H5Pclose};
  hsize_t rows = 0, block = 0, first = 0, size = 0, next_row = 0;
  std::size_t converted = 0;
  std::size_t row_size = 0;
  bool any_variable = false;
  // Chunks read raw and unfiltered here, only the members asked for
  // unshuffled (no HDF5 type conversion), when the file's members are stored
  // as this machine holds them.
  bool raw = false;
  FileRows file_rows;
  std::unique_ptr<GlobalHeapText> heap;  // the raw chunks' variable-length text, made at its first
  std::vector<unsigned char> stored, chunk, member;
  std::vector<Wanted> cols;
  std::vector<std::size_t> slot;  // per column asked for, its entry of cols (a name asked twice is read once)
  std::vector<unsigned char> buf;
  bool read_raw_block();
};

ColumnBlockReader::ColumnBlockReader(const std::string& path, std::vector<std::string> columns, std::size_t block_rows)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.file.id = open_result_file(path);
  H5E_BEGIN_TRY { m.dset.id = H5Dopen2(m.file.id, "/runs", H5P_DEFAULT); }
  H5E_END_TRY;
  if (m.dset.id < 0) input_fail(path + " has no /runs dataset (not a chaosweep result file)");
  Handle ftype{H5Dget_type(m.dset.id), H5Tclose};
  if (H5Tget_class(ftype.id) != H5T_COMPOUND)
    input_fail(path + ": /runs is not a table of columns (not a chaosweep result file)");
  m.fspace.id = H5Dget_space(m.dset.id);
  if (H5Sget_simple_extent_ndims(m.fspace.id) != 1)
    input_fail(path + ": /runs is not a one-dimensional table (not a chaosweep result file)");
  H5Sget_simple_extent_dims(m.fspace.id, &m.rows, nullptr);
  // Blocks of whole chunks: each chunk is inflated once, whatever the columns.
  hsize_t chunk = 1024;
  {
    Handle dcpl{H5Dget_create_plist(m.dset.id), H5Pclose};
    hsize_t c = 0;
    if (H5Pget_layout(dcpl.id) == H5D_CHUNKED && H5Pget_chunk(dcpl.id, 1, &c) == 1 && c > 0) chunk = c;
  }
  const hsize_t want = block_rows ? hsize_t(block_rows) : chunk * default_chunks_per_block;
  m.block = (want + chunk - 1) / chunk * chunk;
  Handle native{H5Tget_native_type(ftype.id, H5T_DIR_ASCEND), H5Tclose};
  std::vector<std::pair<std::string, hid_t>> types;  // member types, closed below
  for (const std::string& name : columns) {
    const auto again = std::find_if(m.cols.begin(), m.cols.end(), [&](const Wanted& w) { return w.name == name; });
    if (again != m.cols.end()) {
      m.slot.push_back(std::size_t(again - m.cols.begin()));
      continue;
    }
    m.slot.push_back(m.cols.size());
    const int idx = H5Tget_member_index(native.id, name.c_str());
    if (idx < 0) {
      std::string list;
      for (const std::string& n : column_names(path)) list += (list.empty() ? "" : ", ") + n;
      input_fail(path + ": /runs has no column '" + name + "' (its columns: " + list + ")");
    }
    Handle mt{H5Tget_member_type(native.id, unsigned(idx)), H5Tclose};
    Wanted w;
    w.name = name;
    w.cls = H5Tget_class(mt.id);
    w.size = H5Tget_size(mt.id);
    w.is_signed = w.cls == H5T_INTEGER && H5Tget_sign(mt.id) == H5T_SGN_2;
    w.variable = w.cls == H5T_STRING && H5Tis_variable_str(mt.id) > 0;
    const bool numeric = (w.cls == H5T_FLOAT || w.cls == H5T_INTEGER) && (w.size == 4 || w.size == 8);
    if (!numeric && w.cls != H5T_STRING)
      input_fail(path + ": column '" + name + "' is of a kind chaosweep does not read (neither a number nor text)");
    w.offset = m.row_size;
    m.row_size += w.size;
    m.any_variable = m.any_variable || w.variable;
    m.cols.push_back(std::move(w));
  }
  m.mem.id = H5Tcreate(H5T_COMPOUND, std::max<std::size_t>(m.row_size, 1));
  for (const Wanted& w : m.cols) {
    Handle mt{H5Tget_member_type(native.id, unsigned(H5Tget_member_index(native.id, w.name.c_str()))), H5Tclose};
    if (H5Tinsert(m.mem.id, w.name.c_str(), w.offset, mt.id) < 0) h5::fail("cannot make a row type for " + path);
  }
  m.file_rows = file_rows_of(m.dset.id);
  m.raw = m.file_rows.row_size > 0 && m.file_rows.deflate_level >= 0 && m.file_rows.chunk_rows == chunk;
  for (Wanted& w : m.cols) {
    if (!m.raw) break;
    const unsigned idx = unsigned(H5Tget_member_index(ftype.id, w.name.c_str()));
    Handle ft{H5Tget_member_type(ftype.id, idx), H5Tclose}, nt{H5Tget_member_type(native.id, idx), H5Tclose};
    m.raw = w.variable ? bool(m.file_rows.variable_text[idx]) : H5Tequal(ft.id, nt.id) > 0;
    w.file_offset = m.file_rows.offsets[idx];
    m.raw = m.raw && w.file_offset + (w.variable ? file_variable_text_size : w.size) <= m.file_rows.row_size;
  }
  // A conversion buffer for a whole block, so HDF5 converts it in one go.
  m.dxpl.id = H5Pcreate(H5P_DATASET_XFER);
  const std::size_t file_row = H5Tget_size(ftype.id);
  H5Pset_buffer(m.dxpl.id, std::max<std::size_t>(std::size_t(m.block) * std::max(file_row, m.row_size), 1 << 20),
                nullptr, nullptr);
}

ColumnBlockReader::~ColumnBlockReader() = default;

std::size_t ColumnBlockReader::rows() const { return std::size_t(impl_->rows); }
std::size_t ColumnBlockReader::block_rows() const { return std::size_t(impl_->block); }
std::size_t ColumnBlockReader::first() const { return std::size_t(impl_->first); }
std::size_t ColumnBlockReader::size() const { return std::size_t(impl_->size); }
std::size_t ColumnBlockReader::blocks_converted() const { return impl_->converted; }

Column::Type ColumnBlockReader::type(std::size_t c) const {
  const H5T_class_t cls = impl_->cols[impl_->slot.at(c)].cls;
  return cls == H5T_FLOAT ? Column::Type::f64 : cls == H5T_INTEGER ? Column::Type::i64 : Column::Type::text;
}

const std::vector<std::int64_t>& ColumnBlockReader::i64(std::size_t c) const {
  const Wanted& w = impl_->cols[impl_->slot.at(c)];
  if (w.cls != H5T_INTEGER) throw std::logic_error(impl_->path + ": column '" + w.name + "' is not integers");
  return w.i64;
}

const std::vector<double>& ColumnBlockReader::f64(std::size_t c) const {
  const Wanted& w = impl_->cols[impl_->slot.at(c)];
  if (w.cls != H5T_FLOAT) throw std::logic_error(impl_->path + ": column '" + w.name + "' is not floats");
  return w.f64;
}

const std::vector<double>& ColumnBlockReader::number(std::size_t c) const {
  const Wanted& w = impl_->cols[impl_->slot.at(c)];
  if (w.cls == H5T_STRING) throw std::logic_error(impl_->path + ": column '" + w.name + "' is not numeric");
  return w.f64;
}

const std::vector<std::string>& ColumnBlockReader::text(std::size_t c) const {
  const Wanted& w = impl_->cols[impl_->slot.at(c)];
  if (w.cls != H5T_STRING) throw std::logic_error(impl_->path + ": column '" + w.name + "' is not text");
  return w.text;
}

// The current block from its chunks as stored: inflated, then of each member
// asked for only its bytes unshuffled, variable-length text from the global
// heap. False (the block then read through HDF5, which names a damaged
// file) when a chunk or the heap is not as expected.
bool ColumnBlockReader::Impl::read_raw_block() {
  Impl& m = *this;
  const hsize_t cr = m.file_rows.chunk_rows;
  const std::size_t chunk_bytes = std::size_t(cr) * m.file_rows.row_size;
  for (Wanted& w : m.cols) prepare(w, std::size_t(m.size));
  m.chunk.resize(chunk_bytes);
  for (hsize_t c = m.first; c < m.first + m.size; c += cr) {
    hsize_t stored = 0;
    std::uint32_t mask = 0;
    if (H5Dget_chunk_storage_size(m.dset.id, &c, &stored) < 0 || stored == 0) return false;
    m.stored.resize(std::size_t(stored));
    herr_t rc;
    H5E_BEGIN_TRY { rc = H5Dread_chunk(m.dset.id, H5P_DEFAULT, &c, &mask, m.stored.data()); }
    H5E_END_TRY;
    if (rc < 0 || mask != 0 || !inflate_exactly(m.stored.data(), m.stored.size(), m.chunk.data(), chunk_bytes))
      return false;
    const std::size_t at = std::size_t(c - m.first), valid = std::size_t(std::min(cr, m.first + m.size - c));
    for (Wanted& w : m.cols) {
      const std::size_t size = w.variable ? file_variable_text_size : w.size;
      m.member.resize(std::size_t(cr) * size);
      transpose_bytes(m.chunk.data() + w.file_offset * std::size_t(cr), size, std::size_t(cr), m.member.data());
      if (w.cls == H5T_FLOAT && w.size == 8) {
        std::memcpy(w.f64.data() + at, m.member.data(), valid * 8);
      } else if (w.variable) {
        for (std::size_t r = 0; r < valid; ++r) {
          const unsigned char* p = m.member.data() + r * size;
          std::string& t = w.text.emplace_back();
          if (empty_variable_text(p)) continue;
          if (!m.heap) m.heap = std::make_unique<GlobalHeapText>(m.file.id);
          if (!m.heap->usable() || !m.heap->text(p, t)) return false;
        }
      } else {
        for (std::size_t r = 0; r < valid; ++r) take(w, at + r, m.member.data() + r * size);
      }
    }
  }
  return true;
}

bool ColumnBlockReader::next() {
  Impl& m = *impl_;
  if (m.next_row >= m.rows) {
    m.first = m.rows;
    m.size = 0;
    return false;
  }
  m.first = m.next_row;
  m.size = std::min(m.block, m.rows - m.first);
  m.next_row += m.size;
  const std::size_t n = std::size_t(m.size);
  if (m.raw && !m.cols.empty() && m.read_raw_block()) return true;
  if (!m.cols.empty()) ++m.converted;
  m.buf.assign(n * m.row_size, 0);
  H5Sselect_hyperslab(m.fspace.id, H5S_SELECT_SET, &m.first, nullptr, &m.size, nullptr);
  Handle mspace{H5Screate_simple(1, &m.size, nullptr), H5Sclose};
  herr_t rc = 0;
  if (!m.cols.empty()) {
    H5E_BEGIN_TRY { rc = H5Dread(m.dset.id, m.mem.id, mspace.id, m.fspace.id, m.dxpl.id, m.buf.data()); }
    H5E_END_TRY;
  }
  if (rc < 0) {
    // The strings HDF5 converted before it failed (the rest are null).
    if (m.any_variable) H5Dvlen_reclaim(m.mem.id, mspace.id, H5P_DEFAULT, m.buf.data());
    input_fail("cannot read /runs of " + m.path + " (rows " + std::to_string(m.first) + "..): the file is damaged");
  }
  const unsigned char* base = m.buf.data();
  for (Wanted& w : m.cols) {
    prepare(w, n);
    for (std::size_t r = 0; r < n; ++r) take(w, r, base + r * m.row_size + w.offset);
  }
  if (m.any_variable) H5Dvlen_reclaim(m.mem.id, mspace.id, H5P_DEFAULT, m.buf.data());
  return true;
}

TypedColumns read_some_columns(const std::string& path, const std::vector<std::string>& columns) {
  ColumnBlockReader reader(path, columns);
  TypedColumns out;
  out.rows = reader.rows();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const Column::Type t = reader.type(c);
    if (t == Column::Type::text) out.text[columns[c]].reserve(out.rows);
    else if (t == Column::Type::i64) out.i64[columns[c]].reserve(out.rows);
    else out.f64[columns[c]].reserve(out.rows);
  }
  while (reader.next()) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (std::find(columns.begin(), columns.begin() + long(c), columns[c]) != columns.begin() + long(c))
        continue;  // asked for twice: taken once
      const Column::Type t = reader.type(c);
      if (t == Column::Type::text) {
        auto& dst = out.text[columns[c]];
        const auto& src = reader.text(c);
        dst.insert(dst.end(), src.begin(), src.end());
      } else if (t == Column::Type::i64) {
        auto& dst = out.i64[columns[c]];
        dst.insert(dst.end(), reader.i64(c).begin(), reader.i64(c).end());
      } else {
        auto& dst = out.f64[columns[c]];
        dst.insert(dst.end(), reader.f64(c).begin(), reader.f64(c).end());
      }
    }
  }
  return out;
}

}  // namespace chaosweep
