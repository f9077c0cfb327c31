#pragma once
// A table as text cells, written as Markdown, CSV or LaTeX. Tables and the
// CSV data beside every figure both go through it.
#include <ostream>
#include <string>
#include <vector>

namespace chaosweep {

enum class TableFormat { md, csv, tex };
// "md", "csv" or "tex"; throws AnalysisError naming the allowed ones.
TableFormat parse_table_format(const std::string& s);

// A cell: its text, and for a number shown rounded (a coverage time to five
// digits) its value in full, which CSV writes so that the data keep every
// digit while Markdown and LaTeX stay readable.
struct Cell {
  std::string shown, full;  // full empty: the same as shown
  Cell(std::string s) : shown(std::move(s)) {}
  Cell(const char* s) : shown(s) {}
  Cell(std::string s, std::string f) : shown(std::move(s)), full(std::move(f)) {}
};

struct TextTable {
  std::string title;  // a caption (md/tex only)
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // each as long as header, as shown
  std::vector<std::vector<std::string>> full;  // per row: the CSV text where a cell has one (else empty)
  std::vector<std::string> notes;              // lines under the table (md/tex only)

  void add_row(std::vector<Cell> r);  // throws when the width is wrong
  void write(std::ostream& os, TableFormat f) const;
  // Writes to `path` atomically: a temporary file renamed at the end.
  void write_file(const std::string& path, TableFormat f) const;
};

// Cell formatting shared by the tables: numbers to `digits` significant
// digits ("-" for NaN), whole numbers without a decimal point.
std::string fmt_sig(double v, int digits = 4);
std::string fmt_fixed(double v, int decimals);
// A number in full: its shortest round-trip form ("-" for NaN).
std::string fmt_full(double v);
// Cells of a computed number: shown as fmt_sig / fmt_fixed, in full in CSV.
Cell sig_cell(double v, int digits = 4);
Cell fixed_cell(double v, int decimals);

}  // namespace chaosweep
