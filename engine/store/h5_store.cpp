// The store's writer: H5RunWriter (layout and crash safety in h5_store.hpp
// and docs/store.md).
#include "engine/store/h5_store.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <deque>
#include <filesystem>
#include <stdexcept>

#include "engine/store/disk_room.hpp"
#include "engine/store/h5_detail.hpp"
#include "engine/store/h5_file_rows.hpp"
#include "engine/store/rollback_driver.hpp"

namespace chaosweep {

namespace fs = std::filesystem;
using h5::Handle;

namespace {

constexpr hsize_t chunk_rows = 1024;

std::string errno_text() { return errno ? std::string(": ") + std::strerror(errno) : std::string(); }

// Member names of a compound type, in order.
std::vector<std::string> member_names(hid_t type) {
  std::vector<std::string> names;
  for (int i = 0; i < H5Tget_nmembers(type); ++i) {
    char* name = H5Tget_member_name(type, unsigned(i));
    names.emplace_back(name);
    H5free_memory(name);
  }
  return names;
}

}  // namespace

template <class Body>
void H5RunWriter::session(const char* what, Body&& body) {
  errno = 0;
  bool ok = false;
  std::string why;
  try {
    open();
    body();
    ok = true;
  } catch (const std::exception& e) {
    why = e.what();
  }
  const int err = errno;
  if (!ok && file_ >= 0) abandon_session(file_);
  const bool closed = close();  // flushes: fails when the disk is full
  if (ok && closed) return;
  try {
    roll_back(partial_);  // the file as before this session
  } catch (const std::exception& e) {
    why += std::string(why.empty() ? "" : "; ") + e.what();
  }
  if (!why.empty()) throw std::runtime_error(why);
  errno = err;
  h5::fail(std::string("cannot ") + what + " " + partial_ + errno_text() + " (the disk may be full)");
}

void H5RunWriter::lay_out(const std::map<std::string, std::size_t>& widths) {
  // Numbers 8 bytes, text fixed-length or a char* (8-byte aligned).
  const auto& cols = result_columns();
  if (type_ >= 0) H5Tclose(type_);
  RowLayout& l = layout_;
  l.offsets.clear();
  l.text_sizes.clear();
  l.row_size = 0;
  std::vector<hid_t> member(cols.size());
  for (std::size_t i = 0; i < cols.size(); ++i) {
    const Column& c = cols[i];
    const auto w = widths.find(c.name);
    const std::size_t size = c.type != Column::Type::text ? 0 : w != widths.end() ? w->second : c.text_size;
    const bool variable = c.type == Column::Type::text && size == 0;
    if (variable) l.row_size = (l.row_size + 7) / 8 * 8;
    l.offsets.push_back(l.row_size);
    l.text_sizes.push_back(size);
    l.row_size += c.type != Column::Type::text ? 8 : variable ? sizeof(char*) : size;
    member[i] = c.type == Column::Type::f64   ? H5Tcopy(H5T_NATIVE_DOUBLE)
                : c.type == Column::Type::i64 ? H5Tcopy(H5T_NATIVE_INT64)
                : variable                    ? h5::variable_text_type()
                                              : h5::fixed_text_type(size);
  }
  l.row_size = (l.row_size + 7) / 8 * 8;
  type_ = H5Tcreate(H5T_COMPOUND, l.row_size);
  for (std::size_t i = 0; i < cols.size(); ++i) {
    H5Tinsert(type_, cols[i].name.c_str(), l.offsets[i], member[i]);
    H5Tclose(member[i]);
  }
}

void H5RunWriter::learn_file_layout(hid_t dset) {
  const auto& cols = result_columns();
  RowLayout& l = layout_;
  l.file_row_size = 0;
  l.file_offsets.assign(cols.size(), 0);
  // Only the filters and chunks this writer sets (shuffle, then deflate).
  const FileRows f = file_rows_of(dset);
  if (f.row_size == 0 || f.deflate_level < 0 || f.chunk_rows != chunk_rows) return;
  Handle ftype{H5Dget_type(dset), H5Tclose};
  if (H5Tget_nmembers(ftype.id) != int(cols.size()) || H5Tget_size(ftype.id) != l.row_size) return;
  for (std::size_t i = 0; i < cols.size(); ++i) {
    Handle mt{H5Tget_member_type(ftype.id, unsigned(i)), H5Tclose};
    const H5T_class_t cls = H5Tget_class(mt.id);
    const std::size_t text = l.text_sizes[i];
    const bool expected =
        H5Tget_member_offset(ftype.id, unsigned(i)) == l.offsets[i] &&
        (cols[i].type == Column::Type::f64   ? H5Tequal(mt.id, H5T_NATIVE_DOUBLE) > 0
         : cols[i].type == Column::Type::i64 ? H5Tequal(mt.id, H5T_NATIVE_INT64) > 0
         : text == 0                         ? cls == H5T_STRING && H5Tis_variable_str(mt.id) > 0
                     : cls == H5T_STRING && H5Tis_variable_str(mt.id) <= 0 && H5Tget_size(mt.id) == text);
    if (!expected) return;
    l.file_offsets[i] = f.offsets[i];
  }
  l.deflate_level = f.deflate_level;
  l.file_row_size = f.row_size;
}

H5RunWriter::H5RunWriter(std::string path, Mode mode, const std::vector<Attribute>& attributes,
                         const std::map<std::string, std::size_t>& text_widths)
    : path_(std::move(path)), partial_(path_ + ".partial") {
  lay_out(text_widths);
  if (mode == Mode::resume) {
    if (!fs::exists(partial_)) h5::fail("no " + partial_ + " to resume");
    session("update", [&] {
      // An older layout (text cut to fixed widths) is read, never extended.
      const htri_t versioned = H5Aexists(file_, "layout_version");
      std::int64_t version = 1;
      if (versioned > 0) {
        Handle a{H5Aopen(file_, "layout_version", H5P_DEFAULT), H5Aclose};
        herr_t rc;
        H5E_BEGIN_TRY { rc = H5Aread(a.id, H5T_NATIVE_INT64, &version); }
        H5E_END_TRY;
        if (rc < 0) version = -1;
      }
      if (version != store_layout_version)
        throw std::runtime_error(partial_ + " is of result-file layout " + std::to_string(version) + ", not " +
                                 std::to_string(store_layout_version) +
                                 " (written by another chaosweep version): it cannot be resumed; its rows stay "
                                 "readable; start over with --force");
      Handle ftype{H5Dget_type(dset_), H5Tclose};
      if (member_names(ftype.id) != member_names(type_))
        throw std::runtime_error(partial_ + " was written by an engine with other columns: cannot resume it");
      std::map<std::string, std::size_t> widths;  // the file's own
      for (int i = 0; i < H5Tget_nmembers(ftype.id); ++i) {
        Handle mt{H5Tget_member_type(ftype.id, unsigned(i)), H5Tclose};
        if (H5Tget_class(mt.id) != H5T_STRING) continue;
        char* name = H5Tget_member_name(ftype.id, unsigned(i));
        widths[name] = H5Tis_variable_str(mt.id) > 0 ? 0 : H5Tget_size(mt.id);
        H5free_memory(name);
      }
      lay_out(widths);
      learn_file_layout(dset_);
      Handle space{H5Dget_space(dset_), H5Sclose};
      hsize_t rows = 0;
      H5Sget_simple_extent_dims(space.id, &rows, nullptr);
      rows_ = prepared_ = rows;
      for (const Attribute& a : attributes) write_attribute(file_, a);
    });
    return;
  }
  const fs::path parent = fs::path(path_).parent_path();
  if (!parent.empty()) fs::create_directories(parent);
  // Made complete under another name, so that OUT.partial, once there, always
  // holds the provenance --resume checks.
  const std::string fresh = partial_ + ".new";
  errno = 0;
  Handle fapl{rollback_fapl(), H5Pclose};
  hid_t file;
  H5E_BEGIN_TRY { file = H5Fcreate(fresh.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id); }
  H5E_END_TRY;
  if (file < 0) h5::fail("cannot create " + fresh + errno_text());
  bool ok = false;
  try {
    hsize_t dims = 0, maxdims = H5S_UNLIMITED;
    Handle space{H5Screate_simple(1, &dims, &maxdims), H5Sclose};
    Handle dcpl{H5Pcreate(H5P_DATASET_CREATE), H5Pclose};
    H5Pset_chunk(dcpl.id, 1, &chunk_rows);
    H5Pset_shuffle(dcpl.id);
    H5Pset_deflate(dcpl.id, 4);
    Handle dset{H5Dcreate2(file, "runs", type_, space.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT), H5Dclose};
    if (dset.id < 0) h5::fail("cannot create /runs in " + fresh);
    learn_file_layout(dset.id);
    write_attribute(file, {"layout_version", store_layout_version});
    for (const Attribute& a : attributes) write_attribute(file, a);
    ok = true;
  } catch (...) {
    H5Fclose(file);
    fs::remove(fresh);
    throw;
  }
  if (H5Fclose(file) < 0 || !ok) {
    fs::remove(fresh);
    h5::fail("cannot write " + fresh + errno_text());
  }
  roll_back(partial_);  // a --force start-over: the old file's journal must not touch the new one
  fs::rename(fresh, partial_);
}

H5RunWriter::~H5RunWriter() {
  close();
  if (type_ >= 0) H5Tclose(type_);
}

void H5RunWriter::open() {
  if (file_ >= 0) return;
  Handle fapl{rollback_fapl(), H5Pclose};
  H5E_BEGIN_TRY { file_ = H5Fopen(partial_.c_str(), H5F_ACC_RDWR, fapl.id); }
  H5E_END_TRY;
  if (file_ < 0) {
    const std::string why = rollback_open_error();
    h5::fail("cannot open " + partial_ + (why.empty() ? " (a damaged partial file cannot be resumed)" : ": " + why));
  }
  H5E_BEGIN_TRY { dset_ = H5Dopen2(file_, "/runs", H5P_DEFAULT); }
  H5E_END_TRY;
  if (dset_ < 0) h5::fail(partial_ + " has no /runs dataset");
}

bool H5RunWriter::close() {
  herr_t rc = 0;
  H5E_BEGIN_TRY {
    if (dset_ >= 0 && H5Dclose(dset_) < 0) rc = -1;
    if (file_ >= 0 && H5Fclose(file_) < 0) rc = -1;
  }
  H5E_END_TRY;
  dset_ = file_ = -1;
  return rc >= 0;
}

void H5RunWriter::set_attribute(const std::string& name, const std::string& value) { set_attributes({{name, value}}); }

void H5RunWriter::set_attributes(const std::vector<Attribute>& attributes) {
  session("write attributes to", [&] {
    for (const Attribute& a : attributes) write_attribute(file_, a);
  });
}

void H5RunWriter::append(const std::vector<RunRow>& rows, const ParallelFor& parallel) {
  try {
    write(prepare(rows, parallel));
  } catch (...) {
    prepared_ = rows_;  // nothing else prepared meanwhile: the next append follows the file
    throw;
  }
}

PreparedRows H5RunWriter::prepare(const std::vector<RunRow>& rows, const ParallelFor& parallel) {
  PreparedRows out;
  out.first_row = prepared_;
  out.n = rows.size();
  if (rows.empty()) return out;
  // Pieces end at the file's chunk boundaries, so each whole chunk is one;
  // their rows are encoded in blocks of `block` rows.
  constexpr std::size_t block = 256;
  const std::size_t n = rows.size();
  auto& pieces = out.pieces;
  auto& parts = out.parts;
  for (std::size_t r = 0; r < n;) {
    const std::size_t to_boundary = chunk_rows - (out.first_row + r) % chunk_rows;
    const std::size_t count = std::min(to_boundary, n - r);
    for (std::size_t b = r; b < r + count; b += block) {
      parts.emplace_back();
      parts.back().first = b;
      parts.back().count = std::min(block, r + count - b);
    }
    pieces.push_back({r, count, parts.size(), {}});
    r += count;
  }
  {
    const std::lock_guard<std::mutex> lock(spare_mutex_);
    if (!spare_.empty()) {
      out.buf = std::move(spare_.back().first);
      out.buf_size = spare_.back().second;
      spare_.pop_back();
    }
  }
  if (out.buf_size < n * layout_.row_size) {
    out.buf = std::make_unique_for_overwrite<unsigned char[]>(n * layout_.row_size);
    out.buf_size = n * layout_.row_size;
  }
  unsigned char* const buf = out.buf.get();
  run_parallel(parallel, parts.size(), [&](std::size_t k) { encode_rows(rows, layout_, partial_, buf, parts[k]); });
  // The pieces that start a chunk are filtered here, the last one too when
  // it ends short of a chunk (padded with zeros as HDF5 pads it: left to
  // HDF5, it was filtered on the sweep's serial thread as the file closed,
  // and a later append into it reads it back through HDF5's filters). A
  // string in the global heap has an address only HDF5 can give: a piece
  // holding one goes through H5Dwrite.
  run_parallel(parallel, pieces.size(), [&](std::size_t k) {
    PreparedRows::Piece& p = pieces[k];
    if ((out.first_row + p.first) % chunk_rows != 0 || layout_.file_row_size == 0) return;
    for (std::size_t j = k ? pieces[k - 1].parts_end : 0; j < p.parts_end; ++j)
      if (!parts[j].texts.empty()) return;
    p.chunk = file_chunk(layout_, buf, p.first, p.count, chunk_rows);
  });
  for (const EncodedRows& p : parts) out.text_bytes += p.text_bytes;
  prepared_ += n;
  return out;
}

std::function<void()> H5RunWriter::prepare_write(const std::vector<RunRow>& rows, const ParallelFor& parallel) {
  // Shared: a std::function must be copyable, the rows are not.
  auto prepared = std::make_shared<PreparedRows>(prepare(rows, parallel));
  return [this, prepared] { write(std::move(*prepared)); };
}

void H5RunWriter::write(PreparedRows rows) {
  if (rows.n == 0) return;
  if (rows.first_row != rows_)
    throw std::logic_error("rows prepared after row " + std::to_string(rows.first_row) + " cannot go to " + partial_ +
                           ", which holds " + std::to_string(rows_) + " (an earlier write failed)");
  const std::size_t n = rows.n;
  // Bound on what the write adds: the rows uncompressed and their text, the
  // last chunk rewritten elsewhere (compressed chunks that grow move) and its
  // old bytes in the journal, and metadata.
  check_room(partial_, (n + 2 * chunk_rows) * layout_.row_size + rows.text_bytes + (512u << 10));
  const hsize_t total = rows_ + n;
  const unsigned char* const buf = rows.buf.get();
  session("write rows to", [&] {
    if (H5Dset_extent(dset_, &total) < 0) h5::fail("cannot extend /runs");
    Handle fspace{H5Dget_space(dset_), H5Sclose};
    for (const PreparedRows::Piece& p : rows.pieces) {
      const hsize_t start = rows_ + p.first, count = p.count;
      herr_t rc;
      if (!p.chunk.empty()) {
        H5E_BEGIN_TRY { rc = H5Dwrite_chunk(dset_, H5P_DEFAULT, 0, &start, p.chunk.size(), p.chunk.data()); }
        H5E_END_TRY;
      } else {
        H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
        Handle mspace{H5Screate_simple(1, &count, nullptr), H5Sclose};
        const unsigned char* from = buf + p.first * layout_.row_size;
        H5E_BEGIN_TRY { rc = H5Dwrite(dset_, type_, mspace.id, fspace.id, H5P_DEFAULT, from); }
        H5E_END_TRY;
      }
      if (rc < 0) h5::fail("cannot write rows to " + partial_ + errno_text() + " (the disk may be full)");
    }
  });
  rows_ = total;
  const std::lock_guard<std::mutex> lock(spare_mutex_);
  if (spare_.size() < 2) spare_.emplace_back(std::move(rows.buf), rows.buf_size);
}

void H5RunWriter::finish() {
  close();
  std::error_code ec;
  fs::remove(journal_path(path_), ec);  // none of this file's: a stale one would mask it
  fs::rename(partial_, path_);
}

}  // namespace chaosweep
