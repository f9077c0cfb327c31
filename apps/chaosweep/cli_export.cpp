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

void write_rows(std::ostream& os, const std::string& file, bool csv) {
  const auto types = column_types(file);
  const TypedColumns cols = read_typed_columns(file);
  if (csv) {
    for (std::size_t c = 0; c < types.size(); ++c) os << (c ? "," : "") << csv_field(types[c].first);
    os << "\n";
  }
  for (std::size_t r = 0; r < cols.rows; ++r) {
    if (!csv) os << "{";
    for (std::size_t c = 0; c < types.size(); ++c) {
      const std::string& name = types[c].first;
      std::string v;
      if (const auto i = cols.i64.find(name); i != cols.i64.end()) {
        v = std::to_string(i->second[r]);
      } else if (const auto f = cols.f64.find(name); f != cols.f64.end()) {
        const double x = f->second[r];
        v = std::isfinite(x) ? format_number(x) : std::isnan(x) ? (csv ? "" : "null") : (x > 0 ? "inf" : "-inf");
        if (!csv && std::isinf(x)) v = "\"" + v + "\"";  // JSON has no infinity
      } else {
        const std::string& t = cols.text.at(name)[r];
        v = csv ? csv_field(t) : "\"" + json_escape(t) + "\"";
      }
      if (csv) os << (c ? "," : "") << v;
      else os << (c ? ", " : "") << "\"" << json_escape(name) << "\": " << v;
    }
    os << (csv ? "\n" : "}\n");
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
    check_result_columns(o.file);  // names a file that is not a result file
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
