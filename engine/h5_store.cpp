#include "h5_store.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>
#include <chrono>

#include <unistd.h>

#include "disk_room.hpp"
#include "result_columns.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

constexpr hsize_t chunk_rows = 1024;

[[noreturn]] void h5_fail(const std::string& what) { throw std::runtime_error("HDF5: " + what); }

hid_t text_type(std::size_t size) {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, size);
  H5Tset_strpad(t, H5T_STR_NULLTERM);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

// What a reader says when a result file cannot be used: the file, and what
// is wrong with it (no "HDF5:" prefix: the user gave a file, not a library).
[[noreturn]] void input_fail(const std::string& what) { throw std::runtime_error(what); }

// Opens a result file read-only and quietly: a failure becomes our own
// message naming the file and what is wrong with it, never HDF5's error
// stack on stderr.
hid_t open_for_reading(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) input_fail(path + " does not exist");
  if (fs::is_directory(path, ec)) input_fail(path + " is a directory, not a result file");
  if (access(path.c_str(), R_OK) != 0) input_fail(path + " cannot be read: " + std::strerror(errno));
  htri_t is_hdf5;
  hid_t f = -1;
  H5E_BEGIN_TRY {
    is_hdf5 = H5Fis_hdf5(path.c_str());
    if (is_hdf5 > 0) f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  H5E_END_TRY;
  if (is_hdf5 <= 0) input_fail(path + " is not an HDF5 file (not a chaosweep result file)");
  if (f < 0) input_fail(path + " is truncated or damaged: HDF5 cannot open it");
  return f;
}

// RAII for the handles of the readers.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

// /runs of a result file, opened read-only, with its row count.
struct RunsDataset {
  Handle file, dset;
  hsize_t rows = 0;
  explicit RunsDataset(const std::string& path) : file{open_for_reading(path), H5Fclose}, dset{-1, H5Dclose} {
    H5E_BEGIN_TRY { dset.id = H5Dopen2(file.id, "/runs", H5P_DEFAULT); }
    H5E_END_TRY;
    if (dset.id < 0) input_fail(path + " has no /runs dataset (not a chaosweep result file)");
    Handle type{H5Dget_type(dset.id), H5Tclose};
    if (H5Tget_class(type.id) != H5T_COMPOUND)
      input_fail(path + ": /runs is not a table of columns (not a chaosweep result file)");
    Handle space{H5Dget_space(dset.id), H5Sclose};
    if (H5Sget_simple_extent_ndims(space.id) != 1)
      input_fail(path + ": /runs is not a one-dimensional table (not a chaosweep result file)");
    H5Sget_simple_extent_dims(space.id, &rows, nullptr);
  }
};

// Reads one member of /runs into a buffer of `member_type` elements.
template <class T>
std::vector<T> read_member(const std::string& path, const std::string& column, hid_t member_type,
                           std::size_t elem_size) {
  const RunsDataset runs(path);
  const hid_t dset_id = runs.dset.id;
  const hsize_t n = runs.rows;
  {
    Handle ftype{H5Dget_type(dset_id), H5Tclose};
    if (H5Tget_member_index(ftype.id, column.c_str()) < 0) input_fail(path + ": /runs has no column '" + column + "'");
  }
  Handle mem{H5Tcreate(H5T_COMPOUND, elem_size), H5Tclose};
  H5Tinsert(mem.id, column.c_str(), 0, member_type);
  std::vector<T> out(n);
  herr_t rc = 0;
  H5E_BEGIN_TRY {
    if (n > 0) rc = H5Dread(dset_id, mem.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  }
  H5E_END_TRY;
  if (rc < 0) input_fail("cannot read column '" + column + "' of " + path + " (the file is damaged or the column's type is foreign)");
  return out;
}

}  // namespace

H5RunWriter::H5RunWriter(std::string path, Mode mode) : path_(std::move(path)), partial_(path_ + ".partial") {
  const auto& cols = result_columns();
  for (const Column& c : cols) {
    offsets_.push_back(row_size_);
    row_size_ += c.type == Column::Type::text ? c.text_size : 8;
  }
  type_ = H5Tcreate(H5T_COMPOUND, row_size_);
  for (std::size_t i = 0; i < cols.size(); ++i) {
    const Column& c = cols[i];
    if (c.type == Column::Type::f64) H5Tinsert(type_, c.name.c_str(), offsets_[i], H5T_NATIVE_DOUBLE);
    else if (c.type == Column::Type::i64) H5Tinsert(type_, c.name.c_str(), offsets_[i], H5T_NATIVE_INT64);
    else {
      hid_t t = text_type(c.text_size);
      H5Tinsert(type_, c.name.c_str(), offsets_[i], t);
      H5Tclose(t);
    }
  }
  if (mode == Mode::resume) {
    if (!fs::exists(partial_)) h5_fail("no " + partial_ + " to resume");
    open();
    hid_t ftype = H5Dget_type(dset_);
    const int n = H5Tget_nmembers(ftype);
    bool same = n == int(cols.size());
    for (int i = 0; same && i < n; ++i) {
      char* name = H5Tget_member_name(ftype, unsigned(i));
      same = cols[std::size_t(i)].name == name;
      H5free_memory(name);
    }
    H5Tclose(ftype);
    hid_t space = H5Dget_space(dset_);
    hsize_t rows = 0;
    H5Sget_simple_extent_dims(space, &rows, nullptr);
    H5Sclose(space);
    rows_ = rows;
    close();
    if (!same) h5_fail(partial_ + " was written by an engine with other columns: cannot resume it");
    return;
  }
  const fs::path parent = fs::path(path_).parent_path();
  if (!parent.empty()) fs::create_directories(parent);
  errno = 0;
  H5E_BEGIN_TRY { file_ = H5Fcreate(partial_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT); }
  H5E_END_TRY;
  if (file_ < 0) h5_fail("cannot create " + partial_ + (errno ? std::string(": ") + std::strerror(errno) : ""));
  hsize_t dims = 0, maxdims = H5S_UNLIMITED;
  hid_t space = H5Screate_simple(1, &dims, &maxdims);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 1, &chunk_rows);
  H5Pset_shuffle(dcpl);
  H5Pset_deflate(dcpl, 4);
  dset_ = H5Dcreate2(file_, "runs", type_, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  H5Sclose(space);
  if (dset_ < 0) h5_fail("cannot create /runs in " + partial_);
  close();
}

H5RunWriter::~H5RunWriter() {
  close();
  if (type_ >= 0) H5Tclose(type_);
}

void H5RunWriter::open() {
  if (file_ >= 0) return;
  // A reader (h5dump, a progress poll) may hold the file for a moment: HDF5's
  // file lock then refuses us; retry for up to ~10 s before giving up.
  for (int attempt = 0; attempt < 100; ++attempt) {
    H5E_BEGIN_TRY { file_ = H5Fopen(partial_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT); }
    H5E_END_TRY;
    if (file_ >= 0 || !fs::exists(partial_)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (file_ < 0) h5_fail("cannot open " + partial_ + " (a damaged partial file cannot be resumed)");
  dset_ = H5Dopen2(file_, "/runs", H5P_DEFAULT);
  if (dset_ < 0) h5_fail(partial_ + " has no /runs dataset");
}

bool H5RunWriter::close() {
  herr_t rc = 0;
  H5E_BEGIN_TRY {
    if (dset_ >= 0 && H5Dclose(dset_) < 0) rc = -1;
    if (file_ >= 0 && H5Fclose(file_) < 0) rc = -1;  // flushes: fails when the disk is full
  }
  H5E_END_TRY;
  dset_ = file_ = -1;
  return rc >= 0;
}

void write_text_attribute(hid_t loc, const std::string& name, const std::string& value) {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  hid_t space = H5Screate(H5S_SCALAR);
  if (H5Aexists(loc, name.c_str()) > 0) H5Adelete(loc, name.c_str());
  hid_t attr = H5Acreate2(loc, name.c_str(), t, space, H5P_DEFAULT, H5P_DEFAULT);
  const char* data = value.c_str();
  const herr_t rc = attr >= 0 ? H5Awrite(attr, t, &data) : -1;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(t);
  if (rc < 0) h5_fail("cannot write attribute " + name);
}

void H5RunWriter::set_attribute(const std::string& name, const std::string& value) {
  open();
  try {
    write_text_attribute(file_, name, value);
  } catch (...) {
    close();
    throw;
  }
  close();
}

void H5RunWriter::append(const std::vector<RunRow>& rows) {
  if (rows.empty()) return;
  const auto& cols = result_columns();
  std::vector<unsigned char> buf(rows.size() * row_size_, 0);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    unsigned char* base = buf.data() + r * row_size_;
    for (std::size_t i = 0; i < cols.size(); ++i) {
      const CellValue v = cols[i].get(rows[r]);
      unsigned char* dst = base + offsets_[i];
      if (const double* d = std::get_if<double>(&v)) std::memcpy(dst, d, 8);
      else if (const std::int64_t* n = std::get_if<std::int64_t>(&v)) std::memcpy(dst, n, 8);
      else {
        const std::string& s = std::get<std::string>(v);
        std::memcpy(dst, s.data(), std::min(s.size(), cols[i].text_size - 1));  // truncated, NUL-ended
      }
    }
  }
  // Bound on what the write adds: the rows uncompressed, the last chunk
  // rewritten elsewhere (compressed chunks that grow move), and metadata.
  check_room(partial_, (rows.size() + chunk_rows) * row_size_ + (256u << 10));
  open();
  const hsize_t start = rows_, count = rows.size(), total = rows_ + rows.size();
  if (H5Dset_extent(dset_, &total) < 0) h5_fail("cannot extend /runs");
  hid_t fspace = H5Dget_space(dset_);
  H5Sselect_hyperslab(fspace, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
  hid_t mspace = H5Screate_simple(1, &count, nullptr);
  errno = 0;
  herr_t rc;
  H5E_BEGIN_TRY { rc = H5Dwrite(dset_, type_, mspace, fspace, H5P_DEFAULT, buf.data()); }
  H5E_END_TRY;
  H5Sclose(mspace);
  H5Sclose(fspace);
  // close(): everything on disk before the next batch starts
  if (!close() || rc < 0)
    h5_fail("cannot write rows to " + partial_ + (errno ? std::string(": ") + std::strerror(errno) : "") +
            " (the disk may be full)");
  rows_ = total;
}

void H5RunWriter::finish() {
  close();
  fs::rename(partial_, path_);
}

std::vector<double> read_f64_column(const std::string& path, const std::string& column) {
  return read_member<double>(path, column, H5T_NATIVE_DOUBLE, sizeof(double));
}

std::vector<std::int64_t> read_i64_column(const std::string& path, const std::string& column) {
  return read_member<std::int64_t>(path, column, H5T_NATIVE_INT64, sizeof(std::int64_t));
}

std::vector<std::string> read_text_column(const std::string& path, const std::string& column) {
  const Column* c = find_column(column);
  const std::size_t size = c && c->type == Column::Type::text ? c->text_size : 256;
  Handle t{text_type(size), H5Tclose};
  struct Fixed {
    char s[256];
  };
  std::vector<Fixed> raw = read_member<Fixed>(path, column, t.id, sizeof(Fixed));
  std::vector<std::string> out;
  for (const Fixed& f : raw) out.emplace_back(f.s, strnlen(f.s, size));
  return out;
}

std::int64_t count_rows(const std::string& path) { return std::int64_t(RunsDataset(path).rows); }

std::vector<std::string> column_names(const std::string& path) {
  const RunsDataset runs(path);
  Handle type{H5Dget_type(runs.dset.id), H5Tclose};
  std::vector<std::string> names;
  for (int i = 0; i < H5Tget_nmembers(type.id); ++i) {
    char* name = H5Tget_member_name(type.id, unsigned(i));
    names.emplace_back(name);
    H5free_memory(name);
  }
  return names;
}

std::vector<std::pair<std::string, Column::Type>> column_types(const std::string& path) {
  const RunsDataset runs(path);
  Handle type{H5Dget_type(runs.dset.id), H5Tclose};
  std::vector<std::pair<std::string, Column::Type>> out;
  for (int i = 0; i < H5Tget_nmembers(type.id); ++i) {
    char* name = H5Tget_member_name(type.id, unsigned(i));
    const H5T_class_t cls = H5Tget_member_class(type.id, unsigned(i));
    const Column::Type t = cls == H5T_FLOAT     ? Column::Type::f64
                           : cls == H5T_INTEGER ? Column::Type::i64
                                                : Column::Type::text;
    out.emplace_back(name, t);
    H5free_memory(name);
  }
  return out;
}

StoredColumns read_all_columns(const std::string& path) {
  const RunsDataset runs(path);
  Handle ftype{H5Dget_type(runs.dset.id), H5Tclose};
  Handle native{H5Tget_native_type(ftype.id, H5T_DIR_ASCEND), H5Tclose};
  const std::size_t row_size = H5Tget_size(native.id);
  struct Member {
    std::size_t offset, size;
    H5T_class_t cls;
    bool is_signed;
    std::size_t index;  // into numeric or text
  };
  StoredColumns out;
  out.rows = std::size_t(runs.rows);
  std::vector<Member> members;
  for (int i = 0; i < H5Tget_nmembers(native.id); ++i) {
    char* name = H5Tget_member_name(native.id, unsigned(i));
    Handle mt{H5Tget_member_type(native.id, unsigned(i)), H5Tclose};
    Member m{H5Tget_member_offset(native.id, unsigned(i)), H5Tget_size(mt.id), H5Tget_class(mt.id),
             H5Tget_class(mt.id) == H5T_INTEGER && H5Tget_sign(mt.id) == H5T_SGN_2, 0};
    const bool ok = (m.cls == H5T_FLOAT && (m.size == 8 || m.size == 4)) ||
                    (m.cls == H5T_INTEGER && (m.size == 8 || m.size == 4)) ||
                    (m.cls == H5T_STRING && !H5Tis_variable_str(mt.id));
    if (ok) {
      if (m.cls == H5T_STRING) {
        m.index = out.text.size();
        out.text.emplace_back(name, std::vector<std::string>{});
        out.text.back().second.reserve(out.rows);
      } else {
        m.index = out.numeric.size();
        out.numeric.emplace_back(name, std::vector<double>{});
        out.numeric.back().second.reserve(out.rows);
      }
      members.push_back(m);
    }
    H5free_memory(name);
  }
  // Blocks of rows bound the memory whatever the file's size.
  const hsize_t block = std::max<hsize_t>(1, (hsize_t(64) << 20) / std::max<std::size_t>(row_size, 1));
  std::vector<unsigned char> buf;
  Handle fspace{H5Dget_space(runs.dset.id), H5Sclose};
  for (hsize_t start = 0; start < runs.rows; start += block) {
    const hsize_t n = std::min(block, runs.rows - start);
    buf.resize(std::size_t(n) * row_size);
    H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, &start, nullptr, &n, nullptr);
    Handle mspace{H5Screate_simple(1, &n, nullptr), H5Sclose};
    herr_t rc;
    H5E_BEGIN_TRY { rc = H5Dread(runs.dset.id, native.id, mspace.id, fspace.id, H5P_DEFAULT, buf.data()); }
    H5E_END_TRY;
    if (rc < 0)
      input_fail("cannot read /runs of " + path + " (rows " + std::to_string(start) + "..): the file is damaged");
    for (hsize_t r = 0; r < n; ++r) {
      const unsigned char* row = buf.data() + std::size_t(r) * row_size;
      for (const Member& m : members) {
        const unsigned char* p = row + m.offset;
        if (m.cls == H5T_STRING) {
          out.text[m.index].second.emplace_back(reinterpret_cast<const char*>(p),
                                                strnlen(reinterpret_cast<const char*>(p), m.size));
          continue;
        }
        double v;
        if (m.cls == H5T_FLOAT && m.size == 8) {
          std::memcpy(&v, p, 8);
        } else if (m.cls == H5T_FLOAT) {
          float f;
          std::memcpy(&f, p, 4);
          v = f;
        } else if (m.size == 8) {
          std::int64_t i;
          std::memcpy(&i, p, 8);
          v = m.is_signed ? double(i) : double(std::uint64_t(i));
        } else {
          std::int32_t i;
          std::memcpy(&i, p, 4);
          v = m.is_signed ? double(i) : double(std::uint32_t(i));
        }
        out.numeric[m.index].second.push_back(v);
      }
    }
  }
  return out;
}

std::string read_attribute(const std::string& path, const std::string& name) {
  Handle file{open_for_reading(path), H5Fclose};
  Handle attr{-1, H5Aclose};
  H5E_BEGIN_TRY { attr.id = H5Aopen(file.id, name.c_str(), H5P_DEFAULT); }
  H5E_END_TRY;
  if (attr.id < 0) input_fail(path + " has no attribute '" + name + "' (not a chaosweep result file?)");
  Handle t{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(t.id, H5T_VARIABLE);
  H5Tset_cset(t.id, H5T_CSET_UTF8);
  char* data = nullptr;
  herr_t rc;
  H5E_BEGIN_TRY { rc = H5Aread(attr.id, t.id, &data); }
  H5E_END_TRY;
  if (rc < 0) input_fail(path + ": cannot read attribute '" + name + "' as text");
  std::string out = data ? data : "";
  H5free_memory(data);
  return out;
}

}  // namespace chaosweep
