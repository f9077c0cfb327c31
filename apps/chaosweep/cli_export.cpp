// `chaosweep export RESULTS.h5 -o runs.csv|runs.jsonl`: the rows of a result
// file for tools that do not read HDF5. Columns in the file's order; numbers
// printed shortest round-trip (they read back to the same doubles); a NaN
// is an empty CSV field or a JSON null. Written beside OUT and renamed, so
// an interrupted export leaves no half file.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/rows/json_writer.hpp"
#include "engine/store/column_blocks.hpp"
#include "engine/store/h5_store.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

struct ExportError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ExportFlags {
  std::string file, out, format;
  bool force = false;
};

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// One column of the file: its key, and where its values are in a block.
struct ExportColumn {
  std::string key;  // the column's name as written before each value (JSON) or in the header (CSV)
  Column::Type type;
};

std::string value_text(const ColumnBlockReader& block, std::size_t c, Column::Type type, std::size_t r, bool csv) {
  if (type == Column::Type::i64) return std::to_string(block.i64(c)[r]);
  if (type == Column::Type::f64) {
    const double x = block.f64(c)[r];
    if (std::isfinite(x)) return format_number(x);
    if (std::isnan(x)) return csv ? "" : "null";
    const std::string inf = x > 0 ? "inf" : "-inf";
    return csv ? inf : "\"" + inf + "\"";  // JSON has no infinity
  }
  const std::string& t = block.text(c)[r];
  if (csv) return csv_field(t);
  // Appended, not "\"" + ...: GCC 12 misreads that temporary's insert (-Wrestrict).
  std::string quoted(1, '"');
  quoted += json_escape(t);
  quoted += '"';
  return quoted;
}

// Block by block (docs/store.md, "Readers"): memory bounded by a block, not
// the file's rows.
void write_rows(std::ostream& os, const std::string& file, bool csv) {
  std::vector<std::string> names;
  std::vector<ExportColumn> columns;
  for (const auto& [name, type] : column_types(file)) {
    names.push_back(name);
    columns.push_back({csv ? csv_field(name) : "\"" + json_escape(name) + "\": ", type});
  }
  ColumnBlockReader block(file, names);
  if (csv) {
    for (std::size_t c = 0; c < columns.size(); ++c) os << (c ? "," : "") << columns[c].key;
    os << "\n";
  }
  std::string line;
  while (block.next()) {
    for (std::size_t r = 0; r < block.size(); ++r) {
      line.clear();
      if (!csv) line += "{";
      for (std::size_t c = 0; c < columns.size(); ++c) {
        if (csv) {
          if (c) line += ",";
        } else {
          if (c) line += ", ";
          line += columns[c].key;
        }
        line += value_text(block, c, columns[c].type, r, csv);
      }
      line += csv ? "\n" : "}\n";
      os << line;
    }
  }
}

int export_command(const ExportFlags& o) {
  return run_reporting<ExportError>("export", [&]() -> int {
    std::string format = o.format;
    if (format.empty()) {
      const std::string ext = std::filesystem::path(o.out).extension().string();
      format = ext == ".jsonl" || ext == ".ndjson" ? "jsonl" : ext == ".csv" ? "csv" : "";
      if (format.empty()) throw ExportError("-o " + o.out + ": give a .csv or .jsonl file, or --format csv|jsonl");
    }
    check_output_free(o.out, o.force);
    try {
      check_result_columns(o.file);  // names a file that is not a result file
    } catch (const std::runtime_error& e) {
      throw ExportError(e.what());  // bad input (exit 2), not an I/O failure
    }
    const std::string tmp = o.out + ".tmp";
    {
      std::ofstream os(tmp);
      if (!os) throw std::runtime_error("cannot write " + tmp);
      write_rows(os, o.file, format == "csv");
      os.flush();
      if (!os) {
        std::filesystem::remove(tmp);
        throw std::runtime_error("cannot write " + tmp + " (disk full?)");
      }
    }
    std::filesystem::rename(tmp, o.out);
    return exit_ok;
  });
}

}  // namespace

void add_export_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("export", "Write the rows of a result file as CSV or JSON Lines");
  cmd->footer(
      "Every column in the file's order, one line per run in run_id order; numbers printed\n"
      "shortest round-trip, NaN as an empty CSV field or a JSON null, text CSV-quoted when it\n"
      "holds a comma, quote or newline. Reads a finished, merged or .partial file.\n"
      "Example: chaosweep export out/demo/results.h5 -o runs.csv");
  auto o = std::make_shared<ExportFlags>();
  cmd->add_option("file", o->file, "result file (.h5)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->out, "output file (.csv or .jsonl)")->required();
  cmd->add_option("--format", o->format, "csv or jsonl (default: from -o's extension)")
      ->check(CLI::IsMember({"csv", "jsonl"}));
  add_force_flag(*cmd, o->force);
  cmd->callback([o, &action] { action = [o] { return export_command(*o); }; });
}

}  // namespace chaosweep
