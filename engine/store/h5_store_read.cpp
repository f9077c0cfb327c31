// The store's readers: result files of either layout, opened quietly (a
// failure is our own message naming the file, never HDF5's error stack) and
// read as of their last finished write (rollback_driver.hpp).
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "engine/store/h5_detail.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/rollback_driver.hpp"

namespace chaosweep {

using h5::Handle;
using h5::input_fail;

namespace {

const char* file_kind(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

// /runs of a result file, opened read-only, with its row count.
struct RunsDataset {
  Handle file, dset;
  hsize_t rows = 0;
  explicit RunsDataset(const std::string& path) : file{open_result_file(path), H5Fclose}, dset{-1, H5Dclose} {
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

// The file type of member `column` of /runs (closed by the caller).
hid_t member_type(const RunsDataset& runs, const std::string& path, const std::string& column) {
  Handle ftype{H5Dget_type(runs.dset.id), H5Tclose};
  const int idx = H5Tget_member_index(ftype.id, column.c_str());
  if (idx < 0) input_fail(path + ": /runs has no column '" + column + "'");
  return H5Tget_member_type(ftype.id, unsigned(idx));
}

// Reads member `column` of /runs into elements of `mem` (of elem_size bytes).
std::vector<unsigned char> read_member(const RunsDataset& runs, const std::string& path, const std::string& column,
                                       hid_t mem, std::size_t elem_size) {
  Handle compound{H5Tcreate(H5T_COMPOUND, elem_size), H5Tclose};
  H5Tinsert(compound.id, column.c_str(), 0, mem);
  std::vector<unsigned char> out(std::size_t(runs.rows) * elem_size);
  herr_t rc = 0;
  H5E_BEGIN_TRY {
    if (runs.rows > 0) rc = H5Dread(runs.dset.id, compound.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  }
  H5E_END_TRY;
  if (rc < 0)
    input_fail("cannot read column '" + column + "' of " + path +
               " (the file is damaged or the column's type is foreign)");
  return out;
}

template <class T>
std::vector<T> read_numeric(const std::string& path, const std::string& column, hid_t mem) {
  const RunsDataset runs(path);
  Handle ft{member_type(runs, path, column), H5Tclose};
  const H5T_class_t cls = H5Tget_class(ft.id);
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) input_fail(path + ": column '" + column + "' is not numeric");
  const std::vector<unsigned char> raw = read_member(runs, path, column, mem, sizeof(T));
  std::vector<T> out(std::size_t(runs.rows));
  if (!out.empty()) std::memcpy(out.data(), raw.data(), raw.size());
  return out;
}

// Text member `m` (of file type `ft`) of each row in `rows` (n rows of
// row_size bytes, read with the native type): variable-length as char*,
// fixed as NUL-padded bytes.
void append_text(std::vector<std::string>& out, const unsigned char* rows, std::size_t n, std::size_t row_size,
                 std::size_t offset, std::size_t size, bool variable) {
  for (std::size_t r = 0; r < n; ++r) {
    const unsigned char* p = rows + r * row_size + offset;
    if (variable) {
      const char* s;
      std::memcpy(&s, p, sizeof s);
      out.emplace_back(s ? s : "");
    } else {
      out.emplace_back(reinterpret_cast<const char*>(p), strnlen(reinterpret_cast<const char*>(p), size));
    }
  }
}

}  // namespace

hid_t open_result_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) input_fail(path + " does not exist");
    input_fail(path + " cannot be read: " + std::strerror(errno));
  }
  // Opening a FIFO or a device could block forever or read without end.
  if (!S_ISREG(st.st_mode)) input_fail(path + " is " + file_kind(st.st_mode) + ", not a result file");
  if (::access(path.c_str(), R_OK) != 0) input_fail(path + " cannot be read: " + std::strerror(errno));
  htri_t is_hdf5;
  H5E_BEGIN_TRY { is_hdf5 = H5Fis_hdf5(path.c_str()); }
  H5E_END_TRY;
  if (is_hdf5 <= 0) input_fail(path + " is not an HDF5 file (not a chaosweep result file)");
  Handle fapl{rollback_fapl(), H5Pclose};
  hid_t f;
  H5E_BEGIN_TRY { f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.id); }
  H5E_END_TRY;
  if (f < 0) {
    const std::string why = rollback_open_error();
    if (why.find("lock") != std::string::npos) input_fail(path + " cannot be read now: " + why + "; try again");
    input_fail(path + " is truncated or damaged: HDF5 cannot open it" + (why.empty() ? "" : " (" + why + ")"));
  }
  return f;
}

std::vector<double> read_f64_column(const std::string& path, const std::string& column) {
  return read_numeric<double>(path, column, H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> read_i64_column(const std::string& path, const std::string& column) {
  return read_numeric<std::int64_t>(path, column, H5T_NATIVE_INT64);
}

std::vector<std::string> read_text_column(const std::string& path, const std::string& column) {
  const RunsDataset runs(path);
  Handle ft{member_type(runs, path, column), H5Tclose};
  if (H5Tget_class(ft.id) != H5T_STRING) input_fail(path + ": column '" + column + "' is not text");
  const bool variable = H5Tis_variable_str(ft.id) > 0;
  Handle mem{H5Tget_native_type(ft.id, H5T_DIR_ASCEND), H5Tclose};  // its own character set (HDF5 converts none)
  const std::size_t size = H5Tget_size(mem.id);
  std::vector<unsigned char> raw = read_member(runs, path, column, mem.id, size);
  std::vector<std::string> out;
  out.reserve(std::size_t(runs.rows));
  append_text(out, raw.data(), std::size_t(runs.rows), size, 0, size, variable);
  if (variable && runs.rows > 0) {
    Handle compound{H5Tcreate(H5T_COMPOUND, size), H5Tclose};
    H5Tinsert(compound.id, column.c_str(), 0, mem.id);
    Handle space{H5Screate_simple(1, &runs.rows, nullptr), H5Sclose};
    H5Dvlen_reclaim(compound.id, space.id, H5P_DEFAULT, raw.data());
  }
  return out;
}

std::int64_t count_rows(const std::string& path) { return std::int64_t(RunsDataset(path).rows); }

std::vector<std::string> column_names(const std::string& path) {
  std::vector<std::string> names;
  for (const auto& [name, type] : column_types(path)) names.push_back(name);
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

void check_result_columns(const std::string& path) {
  const auto types = column_types(path);
  for (const char* key :
       {"run_id", "param_hash", "status", "coverage_time", "variant", "env", "size_x", "size_y", "sr"}) {
    const auto it = std::find_if(types.begin(), types.end(), [&](const auto& t) { return t.first == key; });
    if (it == types.end()) input_fail(path + " has no '" + key + "' column: not a chaosweep result file");
    const bool integer = std::string(key) == "run_id" || std::string(key) == "param_hash";
    if (integer && it->second != Column::Type::i64)
      input_fail(path + ": column '" + key + "' is " + (it->second == Column::Type::f64 ? "floating-point" : "text") +
                 ", not integers: not a chaosweep result file");
  }
}

namespace {

// A member of /runs' native row type that the readers take: numbers of 4 or
// 8 bytes, text of either kind.
struct Member {
  std::string name;
  std::size_t offset, size;
  H5T_class_t cls;
  bool is_signed, variable;
};

double number_at(const Member& m, const unsigned char* p) {
  if (m.cls == H5T_FLOAT && m.size == 8) {
    double v;
    std::memcpy(&v, p, 8);
    return v;
  }
  if (m.cls == H5T_FLOAT) {
    float f;
    std::memcpy(&f, p, 4);
    return f;
  }
  if (m.size == 8) {
    std::int64_t i;
    std::memcpy(&i, p, 8);
    return m.is_signed ? double(i) : double(std::uint64_t(i));
  }
  std::int32_t i;
  std::memcpy(&i, p, 4);
  return m.is_signed ? double(i) : double(std::uint32_t(i));
}

std::int64_t integer_at(const Member& m, const unsigned char* p) {
  if (m.size == 8) {
    std::int64_t i;
    std::memcpy(&i, p, 8);
    return i;
  }
  std::int32_t i;
  std::memcpy(&i, p, 4);
  return m.is_signed ? std::int64_t(i) : std::int64_t(std::uint32_t(i));
}

// Reads /runs in blocks of whole rows (one pass over the compressed chunks,
// however many columns; blocks bound the memory whatever the file's size):
// first `begin(members, rows)`, then `take(member index, rows, n, row_size)`
// for every member and block.
template <class Begin, class Take>
void read_blocks(const std::string& path, Begin&& begin, Take&& take) {
  const RunsDataset runs(path);
  Handle ftype{H5Dget_type(runs.dset.id), H5Tclose};
  Handle native{H5Tget_native_type(ftype.id, H5T_DIR_ASCEND), H5Tclose};
  const std::size_t row_size = H5Tget_size(native.id);
  std::vector<Member> members;
  bool any_variable = false;
  for (int i = 0; i < H5Tget_nmembers(native.id); ++i) {
    char* name = H5Tget_member_name(native.id, unsigned(i));
    Handle mt{H5Tget_member_type(native.id, unsigned(i)), H5Tclose};
    const H5T_class_t cls = H5Tget_class(mt.id);
    const Member m{name,
                   H5Tget_member_offset(native.id, unsigned(i)),
                   H5Tget_size(mt.id),
                   cls,
                   cls == H5T_INTEGER && H5Tget_sign(mt.id) == H5T_SGN_2,
                   cls == H5T_STRING && H5Tis_variable_str(mt.id) > 0};
    H5free_memory(name);
    if ((m.cls == H5T_FLOAT || m.cls == H5T_INTEGER) && (m.size == 8 || m.size == 4)) members.push_back(m);
    if (m.cls == H5T_STRING) members.push_back(m);
    any_variable = any_variable || m.variable;
  }
  begin(static_cast<const std::vector<Member>&>(members), std::size_t(runs.rows));
  const hsize_t block = std::max<hsize_t>(1, (hsize_t(64) << 20) / std::max<std::size_t>(row_size, 1));
  std::vector<unsigned char> buf;
  Handle fspace{H5Dget_space(runs.dset.id), H5Sclose};
  for (hsize_t start = 0; start < runs.rows; start += block) {
    const hsize_t n = std::min(block, runs.rows - start);
    buf.assign(std::size_t(n) * row_size, 0);
    H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, &start, nullptr, &n, nullptr);
    Handle mspace{H5Screate_simple(1, &n, nullptr), H5Sclose};
    herr_t rc;
    H5E_BEGIN_TRY { rc = H5Dread(runs.dset.id, native.id, mspace.id, fspace.id, H5P_DEFAULT, buf.data()); }
    H5E_END_TRY;
    if (rc < 0)
      input_fail("cannot read /runs of " + path + " (rows " + std::to_string(start) + "..): the file is damaged");
    for (std::size_t k = 0; k < members.size(); ++k) take(k, buf.data(), std::size_t(n), row_size);
    if (any_variable) H5Dvlen_reclaim(native.id, mspace.id, H5P_DEFAULT, buf.data());
  }
}

}  // namespace

StoredColumns read_all_columns(const std::string& path) {
  StoredColumns out;
  std::vector<Member> members;
  std::vector<std::size_t> index;  // into numeric or text
  read_blocks(
      path,
      [&](const std::vector<Member>& m, std::size_t rows) {
        members = m;
        out.rows = rows;
        for (const Member& x : members) {
          index.push_back(x.cls == H5T_STRING ? out.text.size() : out.numeric.size());
          if (x.cls == H5T_STRING) out.text.emplace_back(x.name, std::vector<std::string>{});
          else out.numeric.emplace_back(x.name, std::vector<double>{});
        }
      },
      [&](std::size_t k, const unsigned char* rows, std::size_t n, std::size_t row_size) {
        const Member& m = members[k];
        if (m.cls == H5T_STRING) {
          append_text(out.text[index[k]].second, rows, n, row_size, m.offset, m.size, m.variable);
          return;
        }
        std::vector<double>& col = out.numeric[index[k]].second;
        for (std::size_t r = 0; r < n; ++r) col.push_back(number_at(m, rows + r * row_size + m.offset));
      });
  return out;
}

TypedColumns read_typed_columns(const std::string& path) {
  TypedColumns out;
  std::vector<Member> members;
  read_blocks(
      path,
      [&](const std::vector<Member>& m, std::size_t rows) {
        members = m;
        out.rows = rows;
        for (const Member& x : members) {  // every column, of no rows too
          if (x.cls == H5T_STRING) out.text[x.name];
          else if (x.cls == H5T_INTEGER) out.i64[x.name];
          else out.f64[x.name];
        }
      },
      [&](std::size_t k, const unsigned char* rows, std::size_t n, std::size_t row_size) {
        const Member& m = members[k];
        if (m.cls == H5T_STRING) {
          append_text(out.text[m.name], rows, n, row_size, m.offset, m.size, m.variable);
        } else if (m.cls == H5T_INTEGER) {
          auto& col = out.i64[m.name];
          for (std::size_t r = 0; r < n; ++r) col.push_back(integer_at(m, rows + r * row_size + m.offset));
        } else {
          auto& col = out.f64[m.name];
          for (std::size_t r = 0; r < n; ++r) col.push_back(number_at(m, rows + r * row_size + m.offset));
        }
      });
  return out;
}

}  // namespace chaosweep
