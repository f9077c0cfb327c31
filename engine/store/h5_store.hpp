#pragma once
// The HDF5 result store (docs/store.md). Layout 2: one chunked, compressed,
// extendible compound dataset /runs with a row per run (columns from
// result_columns()): numbers as f64/i64; text users or messages write (env,
// label, message) as variable-length UTF-8, never cut; the engine's own words
// (choices, status, variant) as fixed-length UTF-8 wide enough for the
// longest. Provenance as root attributes of their kind: text (variable-length
// UTF-8), numbers (int64), booleans (HDF5 enum FALSE/TRUE over int8, which
// h5py reads as numpy.bool_), and layout_version = 2. Files of layout 1 (all
// text fixed-length, all attributes text) stay readable.
//
// Crash safety: rows go to NAME.partial, which is created complete (dataset
// and provenance) under a temporary name and renamed; every later write (an
// append, an attribute) is one session of the rollback file driver
// (rollback_driver.hpp), so a process killed at any moment leaves the file
// as of its last finished write, which the next open for writing restores
// and every reader here sees. The file is renamed to NAME only by finish().
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "engine/rows/result_columns.hpp"
#include "engine/rows/run_row.hpp"
#include "engine/store/h5_id.hpp"
#include "engine/store/row_chunks.hpp"

namespace chaosweep {

inline constexpr std::int64_t store_layout_version = 2;

// A provenance attribute: text, a number or a boolean.
using AttributeValue = std::variant<std::string, std::int64_t, bool>;
struct Attribute {
  std::string name;
  AttributeValue value;
};

// body(i) for every i in [0, n), possibly on many threads at once, returning
// when all have finished (e.g. ThreadBatchEvaluator::parallel).
using ParallelFor = std::function<void(std::size_t n, const std::function<void(std::size_t)>& body)>;

// body(i) for every i in [0, n): through `parallel`, or in order on this
// thread when it is empty.
inline void run_parallel(const ParallelFor& parallel, std::size_t n, const std::function<void(std::size_t)>& body) {
  if (parallel) {
    parallel(n, body);
  } else {
    for (std::size_t i = 0; i < n; ++i) body(i);
  }
}

class H5RunWriter {
 public:
  enum class Mode { create, resume };
  // create: a new `path`.partial (parent directories too) holding an empty
  // /runs and `attributes` (plus layout_version), made under a temporary
  // name and renamed, so it exists only complete; `text_widths` makes those
  // variable-length text columns fixed-length of that many bytes (see
  // text_widths(spec); a longer value is refused, never cut). resume: an
  // existing one (an interrupted write rolled back first), which must be of
  // this layout and have this engine's columns (its text widths are kept);
  // `attributes` are set on it. The file is closed between writes. Throws
  // std::runtime_error.
  explicit H5RunWriter(std::string path, Mode mode = Mode::create, const std::vector<Attribute>& attributes = {},
                       const std::map<std::string, std::size_t>& text_widths = {});
  ~H5RunWriter();
  H5RunWriter(const H5RunWriter&) = delete;
  H5RunWriter& operator=(const H5RunWriter&) = delete;

  void set_attribute(const std::string& name, const std::string& value);
  void set_attributes(const std::vector<Attribute>& attributes);  // in one write
  // Appends rows in one write: write(prepare(rows, parallel)).
  void append(const std::vector<RunRow>& rows, const ParallelFor& parallel = {});
  // The two halves of an append, so that a sweep can write one batch's rows
  // on a thread of its own while the next batch runs. prepare encodes the
  // rows (and filters each whole chunk without variable-length text:
  // shuffle, deflate) piece by piece through `parallel` (none: on this
  // thread), after the rows prepared before; it touches no HDF5 state.
  // write then writes them in one session: the serial part. Prepared rows
  // are written in the order prepared, one write at a time; prepare may run
  // while a write does. After a failed write, rows prepared since are
  // refused (append forgets them, so a later append may try again).
  PreparedRows prepare(const std::vector<RunRow>& rows, const ParallelFor& parallel = {});
  void write(PreparedRows rows);
  // prepare now; the function returned writes them (run_sweep's RowWrite).
  std::function<void()> prepare_write(const std::vector<RunRow>& rows, const ParallelFor& parallel = {});
  // Closes and renames the partial file to its final name.
  void finish();
  std::size_t rows_written() const { return rows_; }

 private:
  // The row type: each text column fixed-length of widths[name] bytes, else
  // that of result_columns() (0: variable-length).
  void lay_out(const std::map<std::string, std::size_t>& widths);
  // Where the file's row type puts each column (layout_.file_*), so whole
  // chunks can be made off the HDF5 library; none when it is not as expected.
  void learn_file_layout(H5Id dset);
  void open();
  bool close();  // false when flushing failed
  // Runs `body` in one session; on any failure rolls the session back and
  // rethrows (the partial file stays as it was).
  template <class Body>
  void session(const char* what, Body&& body);
  std::string path_, partial_;
  H5Id file_ = -1, dset_ = -1, type_ = -1;
  std::size_t rows_ = 0;
  RowLayout layout_;
  std::size_t prepared_ = 0;  // rows prepared: those the next prepare follows
  // Buffers of written appends, for the next prepare: a fresh buffer per
  // batch cost page faults. Not zeroed when one grows (encode_rows zeroes
  // each block on the thread that fills it), so that the first batch's pages
  // are faulted in on every thread, not the sweep's serial one. Two: one
  // being written, one being prepared.
  std::mutex spare_mutex_;
  std::vector<std::pair<std::unique_ptr<unsigned char[]>, std::size_t>> spare_;
};

// Writes (or replaces) an attribute on `loc` (a file or group: an hid_t). Throws
// std::runtime_error.
void write_attribute(H5Id loc, const Attribute& attribute);
void write_text_attribute(H5Id loc, const std::string& name, const std::string& value);
// Copies every root attribute of `from` but those in `skip` to `to`, each of
// its own type. Throws std::runtime_error naming the file.
void copy_attributes(const std::string& from, H5Id to, const std::set<std::string>& skip);

// "a, b" and "b, c" -> "a, b, c": the names of both comma-separated lists,
// each once, in order of first appearance (provenance such as simd_target).
std::string join_name_lists(const std::string& a, const std::string& b);

// Result files opened for reading (every reader here): a regular file (a
// FIFO, device or directory is refused by name, never opened), HDF5, read as
// of its last finished write. Throws std::runtime_error naming the file.
H5Id open_result_file(const std::string& path);

// Readers for tests and tools: one column of /runs, and root attributes.
std::vector<double> read_f64_column(const std::string& path, const std::string& column);
std::vector<std::int64_t> read_i64_column(const std::string& path, const std::string& column);
std::vector<std::string> read_text_column(const std::string& path, const std::string& column);
// An attribute as text (numbers in decimal, booleans "true"/"false"), for
// files of either layout.
std::string read_attribute(const std::string& path, const std::string& name);
bool has_attribute(const std::string& path, const std::string& name);
// layout_version, 1 for files written before it existed.
std::int64_t layout_version(const std::string& path);

// Every column of /runs at once, read in blocks of whole rows (one pass over
// the compressed chunks, however many columns): integers and floats as
// double (integers exact up to 2^53), strings as text.
struct StoredColumns {
  std::size_t rows = 0;
  std::vector<std::pair<std::string, std::vector<double>>> numeric;
  std::vector<std::pair<std::string, std::vector<std::string>>> text;
};
StoredColumns read_all_columns(const std::string& path);
// The same pass, each column in its file's kind: integers exact (param_hash
// needs all 64 bits), floats, text.
struct TypedColumns {
  std::size_t rows = 0;
  std::map<std::string, std::vector<std::int64_t>> i64;
  std::map<std::string, std::vector<double>> f64;
  std::map<std::string, std::vector<std::string>> text;
};
TypedColumns read_typed_columns(const std::string& path);
std::int64_t count_rows(const std::string& path);
std::vector<std::string> column_names(const std::string& path);
// Names and storage types of /runs' columns, in file order (floats as f64,
// integers as i64, strings as text).
std::vector<std::pair<std::string, Column::Type>> column_types(const std::string& path);

// Throws std::runtime_error naming the file unless /runs has every column a
// chaosweep reader relies on (run_id, param_hash, status, coverage_time,
// variant, env, size_x, size_y, sr), run_id and param_hash as integers.
void check_result_columns(const std::string& path);

}  // namespace chaosweep
