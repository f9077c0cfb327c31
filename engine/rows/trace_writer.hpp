#pragma once
// `run --trace FILE`: the trajectory as CSV (t, x, y, kind, ds_index), one
// row per integration step or transit point.
#include <cstdio>
#include <string>

#include "kernels/core/trace.hpp"

namespace chaosweep {

class CsvTraceWriter : public TraceSink {
 public:
  explicit CsvTraceWriter(const std::string& path);  // throws std::runtime_error
  ~CsvTraceWriter() override;
  CsvTraceWriter(const CsvTraceWriter&) = delete;
  CsvTraceWriter& operator=(const CsvTraceWriter&) = delete;
  void point(const TracePoint& p) override;
  void close();  // throws when the file could not be written completely

 private:
  std::FILE* f_;
  std::string path_;
};

}  // namespace chaosweep
