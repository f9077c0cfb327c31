#pragma once
// Result rows loaded from one or more HDF5 result files into columns: the
// input of every table and figure. Reads files only, never runs anything.
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace chaosweep {

// Bad analysis input (a missing file or column, an empty selection, an
// unknown table/figure name): the message names the offending item.
struct AnalysisError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class ResultSet {
 public:
  // Loads /runs of every file, in order. Columns present in every file are
  // kept (a merged or older file may carry fewer). Throws AnalysisError
  // naming the file when one cannot be read.
  static ResultSet load(const std::vector<std::string>& paths);
  // The same with only `columns` (those the files have) and run_id and
  // status, read block by block (docs/store.md, "Readers"); each of
  // `if_varying` only when it takes more than one value over the rows (a
  // column constant over every row is constant over any of them). A name
  // the files lack is left out: num() and text() then name it and list the
  // files' columns.
  static ResultSet load(const std::vector<std::string>& paths, const std::vector<std::string>& columns,
                        const std::vector<std::string>& if_varying = {});
  // For tests and tools: columns given directly (each of the same length).
  static ResultSet from_columns(std::map<std::string, std::vector<double>> numeric,
                                std::map<std::string, std::vector<std::string>> text);

  std::size_t rows() const { return rows_; }
  const std::vector<std::string>& sources() const { return sources_; }
  bool has(const std::string& name) const { return num_.count(name) || text_.count(name); }
  bool is_numeric(const std::string& name) const { return num_.count(name) > 0; }
  // Numeric column (integers converted to double; exact up to 2^53). Throws
  // AnalysisError naming the column, and listing the available ones.
  const std::vector<double>& num(const std::string& name) const;
  const std::vector<std::string>& text(const std::string& name) const;
  // Any column's value as text (numbers in the shortest round-trip form).
  std::string cell(const std::string& name, std::size_t row) const;
  std::vector<std::string> names() const;
  // Every column the files share, loaded or not (for messages).
  const std::vector<std::string>& file_columns() const { return file_columns_; }
  // The rows whose columns equal the given values ("COL=VALUE", numbers
  // compared as numbers); throws AnalysisError naming a bad condition, or a
  // condition that matches no row (with the values its column takes), or
  // saying that conditions each matching rows match none together.
  ResultSet where(const std::vector<std::string>& conditions) const;

 private:
  static ResultSet load_some(const std::vector<std::string>& paths, const std::vector<std::string>* columns,
                             const std::vector<std::string>& if_varying);
  [[noreturn]] void missing(const std::string& name, const char* kind) const;
  std::size_t rows_ = 0;
  std::vector<std::string> sources_;
  std::vector<std::string> file_columns_;
  std::map<std::string, std::vector<double>> num_;
  std::map<std::string, std::vector<std::string>> text_;
};

// Row indices where `status` is "ok" (runs that reached the coverage target).
std::vector<std::size_t> ok_rows(const ResultSet& rs, const std::vector<std::size_t>& rows);
std::vector<std::size_t> all_rows(const ResultSet& rs);

}  // namespace chaosweep
