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
  offsets_.clear();
  text_sizes_.clear();
  row_size_ = 0;
  std::vector<hid_t> member(cols.size());
  for (std::size_t i = 0; i < cols.size(); ++i) {
    const Column& c = cols[i];
    const auto w = widths.find(c.name);
    const std::size_t size = c.type != Column::Type::text ? 0 : w != widths.end() ? w->second : c.text_size;
    const bool variable = c.type == Column::Type::text && size == 0;
    if (variable) row_size_ = (row_size_ + 7) / 8 * 8;
    offsets_.push_back(row_size_);
    text_sizes_.push_back(size);
    row_size_ += c.type != Column::Type::text ? 8 : variable ? sizeof(char*) : size;
    member[i] = c.type == Column::Type::f64   ? H5Tcopy(H5T_NATIVE_DOUBLE)
                : c.type == Column::Type::i64 ? H5Tcopy(H5T_NATIVE_INT64)
                : variable                    ? h5::variable_text_type()
                                              : h5::fixed_text_type(size);
  }
  row_size_ = (row_size_ + 7) / 8 * 8;
  type_ = H5Tcreate(H5T_COMPOUND, row_size_);
  for (std::size_t i = 0; i < cols.size(); ++i) {
    H5Tinsert(type_, cols[i].name.c_str(), offsets_[i], member[i]);
    H5Tclose(member[i]);
  }
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
      Handle space{H5Dget_space(dset_), H5Sclose};
      hsize_t rows = 0;
      H5Sget_simple_extent_dims(space.id, &rows, nullptr);
      rows_ = rows;
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

void H5RunWriter::append(const std::vector<RunRow>& rows) {
  if (rows.empty()) return;
  const auto& cols = result_columns();
  std::vector<unsigned char> buf(rows.size() * row_size_, 0);
  std::deque<std::string> texts;  // the variable-length strings, alive (and in place) until written
  std::size_t text_bytes = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    unsigned char* base = buf.data() + r * row_size_;
    for (std::size_t i = 0; i < cols.size(); ++i) {
      CellValue v = cols[i].get(rows[r]);
      unsigned char* dst = base + offsets_[i];
      if (const double* d = std::get_if<double>(&v)) {
        std::memcpy(dst, d, 8);
      } else if (const std::int64_t* n = std::get_if<std::int64_t>(&v)) {
        std::memcpy(dst, n, 8);
      } else if (text_sizes_[i] == 0) {
        // "" as a null pointer: HDF5 then stores no heap object, and the
        // row's reference is zeros, which compress away.
        std::string& text = std::get<std::string>(v);
        if (text.empty()) continue;
        texts.push_back(std::move(text));
        const char* p = texts.back().c_str();
        std::memcpy(dst, &p, sizeof p);
        text_bytes += texts.back().size() + 32;  // with the global heap's per-object overhead
      } else {
        const std::string& s = std::get<std::string>(v);
        // Widths are made to fit (the engine's words, text_widths(spec)): a
        // longer value is refused, never cut.
        if (s.size() >= text_sizes_[i])
          throw std::logic_error("column '" + cols[i].name + "' of " + partial_ + " holds " +
                                 std::to_string(text_sizes_[i] - 1) + " bytes, but run " +
                                 std::to_string(rows[r].tuple.run_id) + " has " + std::to_string(s.size()) + ": '" + s +
                                 "'");
        std::memcpy(dst, s.data(), s.size());
      }
    }
  }
  // Bound on what the write adds: the rows uncompressed and their text, the
  // last chunk rewritten elsewhere (compressed chunks that grow move) and its
  // old bytes in the journal, and metadata.
  check_room(partial_, (rows.size() + 2 * chunk_rows) * row_size_ + text_bytes + (512u << 10));
  const hsize_t start = rows_, count = rows.size(), total = rows_ + rows.size();
  session("write rows to", [&] {
    if (H5Dset_extent(dset_, &total) < 0) h5::fail("cannot extend /runs");
    Handle fspace{H5Dget_space(dset_), H5Sclose};
    H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
    Handle mspace{H5Screate_simple(1, &count, nullptr), H5Sclose};
    herr_t rc;
    H5E_BEGIN_TRY { rc = H5Dwrite(dset_, type_, mspace.id, fspace.id, H5P_DEFAULT, buf.data()); }
    H5E_END_TRY;
    if (rc < 0) h5::fail("cannot write rows to " + partial_ + errno_text() + " (the disk may be full)");
  });
  rows_ = total;
}

void H5RunWriter::finish() {
  close();
  std::error_code ec;
  fs::remove(journal_path(path_), ec);  // none of this file's: a stale one would mask it
  fs::rename(partial_, path_);
}

}  // namespace chaosweep
