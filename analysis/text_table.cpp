#include "analysis/text_table.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "analysis/result_set.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

TableFormat parse_table_format(const std::string& s) {
  if (s == "md") return TableFormat::md;
  if (s == "csv") return TableFormat::csv;
  if (s == "tex") return TableFormat::tex;
  throw AnalysisError("--format: unknown format '" + s + "' (allowed: md, csv, tex)");
}

void TextTable::add_row(std::vector<Cell> r) {
  if (r.size() != header.size())
    throw std::logic_error("table row of " + std::to_string(r.size()) + " cells under " +
                           std::to_string(header.size()) + " columns");
  std::vector<std::string> shown, precise;
  bool rounded = false;
  for (const Cell& c : r) rounded = rounded || (!c.full.empty() && c.full != c.shown);
  for (Cell& c : r) {
    if (rounded) precise.push_back(c.full.empty() ? c.shown : std::move(c.full));
    shown.push_back(std::move(c.shown));
  }
  rows.push_back(std::move(shown));
  full.push_back(std::move(precise));
}

namespace {

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string md_cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string tex_cell(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
      case '%':
      case '$':
      case '#':
      case '_':
      case '{':
      case '}':
        out += '\\';
        out += c;
        break;
      case '~':
        out += "\\textasciitilde{}";
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      case '\\':
        out += "\\textbackslash{}";
        break;
      default:
        out += c;
    }
  }
  return out;
}

void write_line(std::ostream& os, const std::vector<std::string>& cells, TableFormat f) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    switch (f) {
      case TableFormat::csv:
        os << (i ? "," : "") << csv_cell(cells[i]);
        break;
      case TableFormat::md:
        os << "| " << md_cell(cells[i]) << " ";
        break;
      case TableFormat::tex:
        os << (i ? " & " : "") << tex_cell(cells[i]);
        break;
    }
  }
  if (f == TableFormat::md) os << "|";
  if (f == TableFormat::tex) os << " \\\\";
  os << "\n";
}

}  // namespace

void TextTable::write(std::ostream& os, TableFormat f) const {
  switch (f) {
    case TableFormat::csv:
      write_line(os, header, f);
      for (std::size_t i = 0; i < rows.size(); ++i)
        write_line(os, i < full.size() && !full[i].empty() ? full[i] : rows[i], f);
      return;
    case TableFormat::md:
      if (!title.empty()) os << "**" << md_cell(title) << "**\n\n";
      write_line(os, header, f);
      for (std::size_t i = 0; i < header.size(); ++i) os << "|---";
      os << "|\n";
      for (const auto& r : rows) write_line(os, r, f);
      if (!notes.empty()) os << "\n";
      for (const std::string& n : notes) os << n << "\n";
      return;
    case TableFormat::tex:
      os << "\\begin{table}\n\\centering\n";
      if (!title.empty()) os << "\\caption{" << tex_cell(title) << "}\n";
      os << "\\begin{tabular}{" << std::string(header.size(), 'l') << "}\n\\hline\n";
      write_line(os, header, f);
      os << "\\hline\n";
      for (const auto& r : rows) write_line(os, r, f);
      os << "\\hline\n\\end{tabular}\n";
      for (const std::string& n : notes) os << "\\par\\small " << tex_cell(n) << "\n";
      os << "\\end{table}\n";
      return;
  }
}

void TextTable::write_file(const std::string& path, TableFormat f) const {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw AnalysisError("cannot write " + path);
    write(out, f);
    out.flush();
    if (!out) throw AnalysisError("cannot write " + path + " (disk full?)");
  }
  fs::rename(tmp, target);
}

std::string fmt_sig(double v, int digits) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  // Whole numbers, and numbers with at least `digits` integer digits, print
  // without exponent (coverage times read as 12346, not 1.235e+04).
  if ((v == std::round(v) || std::fabs(v) >= std::pow(10.0, digits - 1)) && std::fabs(v) < 1e15) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string fmt_fixed(double v, int decimals) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string fmt_full(double v) { return std::isnan(v) ? "-" : format_number(v); }

Cell sig_cell(double v, int digits) { return {fmt_sig(v, digits), fmt_full(v)}; }

Cell fixed_cell(double v, int decimals) { return {fmt_fixed(v, decimals), fmt_full(v)}; }

}  // namespace chaosweep
