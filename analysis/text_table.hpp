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

struct TextTable {
  std::string title;                           // a caption (md/tex only)
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // each as long as header
  std::vector<std::string> notes;              // lines under the table (md/tex only)

  void add_row(std::vector<std::string> r);    // throws when the width is wrong
  void write(std::ostream& os, TableFormat f) const;
  // Writes to `path` atomically: a temporary file renamed at the end.
  void write_file(const std::string& path, TableFormat f) const;
};

// Cell formatting shared by the tables: numbers to `digits` significant
// digits ("-" for NaN), whole numbers without a decimal point.
std::string fmt_sig(double v, int digits = 4);
std::string fmt_fixed(double v, int decimals);

}  // namespace chaosweep
