#include "engine/rows/trace_writer.hpp"

#include <filesystem>
#include <stdexcept>

#include "kernels/core/param_table.hpp"

namespace chaosweep {

CsvTraceWriter::CsvTraceWriter(const std::string& path) : path_(path) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  f_ = std::fopen(path.c_str(), "w");
  if (!f_) throw std::runtime_error("cannot write trace file " + path);
  std::fputs("t,x,y,kind,ds_index\n", f_);
}

CsvTraceWriter::~CsvTraceWriter() {
  if (f_) std::fclose(f_);
}

void CsvTraceWriter::point(const TracePoint& p) {
  std::fprintf(f_, "%s,%s,%s,%s,%d\n", format_number(p.t).c_str(), format_number(p.x).c_str(),
               format_number(p.y).c_str(), to_string(p.kind), p.ds_index);
}

void CsvTraceWriter::close() {
  const bool bad = std::ferror(f_) != 0;
  const bool close_failed = std::fclose(f_) != 0;
  f_ = nullptr;
  if (bad || close_failed) throw std::runtime_error("writing trace file " + path_ + " failed");
}

}  // namespace chaosweep
