#pragma once
// The HDF5 result store (first layout): one chunked, compressed, extendible
// compound dataset /runs with a row per run (columns from result_columns()),
// and provenance as UTF-8 string attributes on the root group.
//
// Crash safety: rows go to NAME.partial, flushed after every append; the file
// is renamed to NAME only by finish().
#include <hdf5.h>

#include <map>
#include <string>
#include <vector>

#include "result_columns.hpp"
#include "run_tuple.hpp"

namespace chaosweep {

class H5RunWriter {
 public:
  enum class Mode { create, resume };
  // create: a new `path`.partial (parent directories too); resume: append to
  // an existing one, whose /runs must have this engine's columns. The file is
  // closed between appends, so a killed process leaves a readable partial
  // file holding every batch appended so far. Throws std::runtime_error.
  explicit H5RunWriter(std::string path, Mode mode = Mode::create);
  ~H5RunWriter();
  H5RunWriter(const H5RunWriter&) = delete;
  H5RunWriter& operator=(const H5RunWriter&) = delete;

  void set_attribute(const std::string& name, const std::string& value);
  void append(const std::vector<RunRow>& rows);
  // Closes and renames the partial file to its final name.
  void finish();
  std::size_t rows_written() const { return rows_; }

 private:
  void open();
  bool close();  // false when flushing failed
  std::string path_, partial_;
  hid_t file_ = -1, dset_ = -1, type_ = -1;
  std::size_t row_size_ = 0, rows_ = 0;
  std::vector<std::size_t> offsets_;
};

// Writes (or replaces) a scalar variable-length UTF-8 string attribute on
// `loc` (a file or group). Throws std::runtime_error.
void write_text_attribute(hid_t loc, const std::string& name, const std::string& value);

// Readers for tests and tools: one column of /runs, and root attributes.
std::vector<double> read_f64_column(const std::string& path, const std::string& column);
std::vector<std::int64_t> read_i64_column(const std::string& path, const std::string& column);
std::vector<std::string> read_text_column(const std::string& path, const std::string& column);
std::string read_attribute(const std::string& path, const std::string& name);

// Every column of /runs at once, read in blocks of whole rows (one pass over
// the compressed chunks, however many columns): integers and floats as
// double (integers exact up to 2^53), strings as text.
struct StoredColumns {
  std::size_t rows = 0;
  std::vector<std::pair<std::string, std::vector<double>>> numeric;
  std::vector<std::pair<std::string, std::vector<std::string>>> text;
};
StoredColumns read_all_columns(const std::string& path);
std::int64_t count_rows(const std::string& path);
std::vector<std::string> column_names(const std::string& path);
// Names and storage types of /runs' columns, in file order (floats as f64,
// integers as i64, strings as text).
std::vector<std::pair<std::string, Column::Type>> column_types(const std::string& path);

}  // namespace chaosweep
